#include "surfgrow/render/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "surfgrow/render/font.hpp"

namespace surfgrow::render {

namespace {

std::optional<Font> load_font(const RenderOptions& options, int px) {
    const auto file =
        options.font_file.empty() ? Font::find_default() : std::optional(options.font_file);
    if (!file) return std::nullopt;
    return Font(*file, px);
}

// A round length near `target` (1, 2 or 5 times a power of ten) and its label.
double nice_length(double target) {
    const double p = std::pow(10.0, std::floor(std::log10(target)));
    for (double m : {5.0, 2.0, 1.0})
        if (m * p <= target) return m * p;
    return p;
}

std::string length_label(double length, const std::string& units) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", length);
    return units.empty() ? std::string(buf) : std::string(buf) + " " + units;
}

// Axis triad: x red, y green, z blue, each the projection of a world axis, labelled past its
// tip; an axis along the view direction is a small ring (a dot in it: towards the viewer, a
// cross: away). Placed left of `right`, centred on row `cy` but kept `bottom_gap` clear of the
// image's bottom edge (it may reach up into the scene's margin); returns its left edge.
int draw_triad(Image& image, const Camera& camera, const Font* font, int right, int cy, int length,
               int bottom_gap) {
    static constexpr Rgb kAxisColor[3] = {{205, 50, 50}, {40, 150, 60}, {50, 90, 210}};
    static constexpr const char* kAxisName[3] = {"x", "y", "z"};
    const double em = font ? font->pixel_size() : 0.0;
    const double width = std::max(1.5, length / 18.0);
    struct Axis {
        double tx, ty;  // tip, relative to the origin
        double lx, ly;  // label centre
        double planar;  // length on screen / length
        bool towards;   // points at the viewer
    };
    Axis axes[3];
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // box of the whole triad around the origin
    for (int k = 0; k < 3; ++k) {
        const Vec3d c = camera.to_camera(Vec3d::Unit(k));
        Axis& a = axes[k];
        a.planar = std::hypot(c.x(), c.y());
        a.towards = c.z() > 0;
        a.tx = c.x() * length, a.ty = -c.y() * length;
        if (a.planar > 0.2) {
            a.lx = a.tx + c.x() / a.planar * em * 0.6, a.ly = a.ty - c.y() / a.planar * em * 0.6;
        } else {  // label below left of the ring
            a.lx = -em * 0.7, a.ly = em * 0.7;
        }
        x0 = std::min({x0, a.tx, a.lx - em * 0.4}), x1 = std::max({x1, a.tx, a.lx + em * 0.4});
        y0 = std::min({y0, a.ty, a.ly - em * 0.5}), y1 = std::max({y1, a.ty, a.ly + em * 0.5});
    }
    const double ox = right - x1;
    const double oy = std::min(cy - (y0 + y1) / 2, image.height() - bottom_gap - y1);
    // Axes pointing away from the viewer first, so nearer ones cross over them.
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3,
              [&](int a, int b) { return camera.forward()[a] > camera.forward()[b]; });
    for (int k : order) {
        const Axis& a = axes[k];
        const Rgb color = kAxisColor[k];
        if (a.planar > 0.2) {
            draw_line(image, ox, oy, ox + a.tx, oy + a.ty, width, color);
        } else {
            const double r = std::max(3.0, length / 6.0);
            for (int i = 0; i < 24; ++i) {  // the ring, as a polygon
                const double t0 = i * M_PI / 12, t1 = (i + 1) * M_PI / 12;
                draw_line(image, ox + r * std::cos(t0), oy + r * std::sin(t0),
                          ox + r * std::cos(t1), oy + r * std::sin(t1), width * 0.8, color);
            }
            if (a.towards) {
                draw_line(image, ox, oy, ox, oy, width * 1.6, color);
            } else {
                const double d = r * 0.6;
                draw_line(image, ox - d, oy - d, ox + d, oy + d, width * 0.8, color);
                draw_line(image, ox - d, oy + d, ox + d, oy - d, width * 0.8, color);
            }
        }
        if (!font) continue;
        const int w = font->measure(kAxisName[k]);
        font->draw(image, static_cast<int>(std::lround(ox + a.lx - w / 2.0)),
                   static_cast<int>(std::lround(oy + a.ly + font->ascent() * 0.38)), kAxisName[k],
                   color);
    }
    return static_cast<int>(std::floor(ox + x0));
}

}  // namespace

OverlayLayout overlay_layout(const RenderOptions& options, bool has_legend) {
    OverlayLayout layout;
    layout.font_px = std::clamp(static_cast<int>(std::lround(options.height / 50.0)), 9, 96);
    const bool any = (options.legend && has_legend) || options.axes || options.scale_bar;
    layout.band_height = any ? static_cast<int>(std::lround(layout.font_px * 2.4)) : 0;
    return layout;
}

void draw_line(Image& image, double x0, double y0, double x1, double y1, double width, Rgb color) {
    const double hw = width / 2;
    const int xa = std::max(0, static_cast<int>(std::floor(std::min(x0, x1) - hw - 1)));
    const int xb = std::min(image.width() - 1, static_cast<int>(std::ceil(std::max(x0, x1) + hw)));
    const int ya = std::max(0, static_cast<int>(std::floor(std::min(y0, y1) - hw - 1)));
    const int yb = std::min(image.height() - 1, static_cast<int>(std::ceil(std::max(y0, y1) + hw)));
    const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
    for (int y = ya; y <= yb; ++y) {
        for (int x = xa; x <= xb; ++x) {
            const double px = x + 0.5 - x0, py = y + 0.5 - y0;
            const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
            const double dist = std::hypot(px - t * dx, py - t * dy);
            const double coverage = std::clamp(hw + 0.5 - dist, 0.0, 1.0);  // 1 px ramp
            if (coverage > 0) image.blend(x, y, color, coverage);
        }
    }
}

void draw_overlays(Image& image, const std::string& legend, const Camera& camera,
                   const RenderOptions& options) {
    const OverlayLayout layout = overlay_layout(options, !legend.empty());
    if (layout.band_height == 0) return;
    const int band_top = image.height() - layout.band_height;
    const int cy = band_top + layout.band_height / 2;
    const int pad = layout.font_px;
    std::optional<Font> font = load_font(options, layout.font_px);
    const Font* f = font ? &*font : nullptr;

    int right = image.width() - pad;  // what is drawn right to left ends here
    if (options.axes)
        right = draw_triad(image, camera, f, right, cy, layout.font_px * 7 / 4, pad / 3);
    if (options.scale_bar && !options.camera) {
        const double length = nice_length(image.width() * 0.12 / camera.scale());
        const double px = length * camera.scale();
        // The camera is orthographic: a length is true wherever it lies square to the view. In
        // front, side and top views that is the axis planes; in iso views and close-ups, say so.
        const bool oblique = options.close_up || options.view == View::kIso;
        const std::string label =
            length_label(length, options.units) + (oblique ? " across the view" : "");
        const int label_w = f ? f->measure(label) : 0;
        const double x1 = right - pad, x0 = x1 - px;
        const double y = cy + layout.font_px * 0.15;
        const double tick = layout.font_px * 0.35;
        const Rgb ink = options.text_color;
        draw_line(image, x0, y, x1, y, 2.0, ink);
        draw_line(image, x0, y - tick, x0, y + tick, 2.0, ink);
        draw_line(image, x1, y - tick, x1, y + tick, 2.0, ink);
        if (f)
            f->draw(image, static_cast<int>(std::lround(x0 - pad / 2.0 - label_w)),
                    static_cast<int>(std::lround(y + f->ascent() * 0.38)), label, ink);
        right = static_cast<int>(x0) - label_w - pad;
    }
    if (options.legend && !legend.empty() && f) {
        int size = layout.font_px;
        std::optional<Font> small;
        const Font* text_font = f;
        // Shrink a legend too long for the room left of the triad rather than clip it.
        const int room = right - pad - pad;
        const int w = f->measure(legend);
        if (w > room && room > 0) {
            size = std::max(8, size * room / w);
            small = load_font(options, size);
            text_font = &*small;
        }
        text_font->draw(image, pad, cy + text_font->ascent() * 3 / 8, legend, options.text_color);
    }
}

}  // namespace surfgrow::render
