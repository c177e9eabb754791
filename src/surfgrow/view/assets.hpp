// The files the viewer page is made of, embedded into the library at build time
// (cmake/embed_files.cmake): nothing is read from disk or the network when a page is written.
#pragma once

#include <string_view>

namespace surfgrow::view::assets {

/// three.min.js of Debian's libjs-three (r111, MIT licence).
[[nodiscard]] std::string_view three_js();
/// examples/js/controls/OrbitControls.js of the same package (adds THREE.OrbitControls).
[[nodiscard]] std::string_view orbit_controls_js();
/// viewer.html: the page, with @NAME@ markers where write_viewer_html() puts the rest.
[[nodiscard]] std::string_view page_template();
/// viewer.css and viewer.js: the page's style and script.
[[nodiscard]] std::string_view page_css();
[[nodiscard]] std::string_view page_js();

}  // namespace surfgrow::view::assets
