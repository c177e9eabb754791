// The 2D layer over the rendered scene: legend line, axis triad, scale bar.
#pragma once

#include <string>

#include "surfgrow/render/camera.hpp"
#include "surfgrow/render/image.hpp"
#include "surfgrow/render/renderer.hpp"

namespace surfgrow::render {

/// Where the overlays go: a band across the bottom of the picture, kept free of the scene.
struct OverlayLayout {
    int band_height = 0;  ///< pixels at the bottom of the image (0: no overlays)
    int font_px = 0;      ///< legend text size
};

/// The band for a picture of options.width x options.height: text about 1/50 of the height.
[[nodiscard]] OverlayLayout overlay_layout(const RenderOptions& options, bool has_legend);

/// Draws the legend text (left), scale bar and axis triad (right) into the band.
void draw_overlays(Image& image, const std::string& legend, const Camera& camera,
                   const RenderOptions& options);

/// An antialiased line `width` pixels wide with round ends, blended over the image.
void draw_line(Image& image, double x0, double y0, double x1, double y1, double width, Rgb color);

}  // namespace surfgrow::render
