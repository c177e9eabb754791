// Writing the viewer: one self-contained HTML file (three.js, the page and the data inline).
#pragma once

#include <ostream>
#include <string>

#include "surfgrow/view/viewer_scene.hpp"

namespace surfgrow::view {

/// Writes `scene` as one HTML page that needs nothing else: no network, no other file. Arrays
/// travel as base64 of little-endian Float32 (positions relative to the scene's centre) and
/// Uint8 (colours); the rest as JSON (docs/viewer.md). Deterministic: the same scene gives the
/// same bytes. Throws Error(kCannotWrite) if `out` fails.
void write_viewer_html(std::ostream& out, const ViewerScene& scene);

/// The same page as a string (tests).
[[nodiscard]] std::string viewer_html(const ViewerScene& scene);

}  // namespace surfgrow::view
