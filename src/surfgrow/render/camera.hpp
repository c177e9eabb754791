// Orthographic cameras: the view presets, projection to pixels, and fitting a scene into a frame.
#pragma once

#include <string_view>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow::render {

/// The named views. World axes: z is up. Each view is a direction to look along:
///   front  looks along +y (from -y): x to the right, z up
///   side   looks along -x (from +x): y to the right, z up
///   top    looks along -z (from above): x to the right, y up
///   iso    looks along (-1, +1, -1) (from the front-right-above corner): z up, x to the lower
///          right, y to the upper right; the three axis planes get three different shades
enum class View { kFront, kSide, kTop, kIso };

/// "front", "side", "top" or "iso"; anything else throws Error(kInvalidParameter).
[[nodiscard]] View parse_view(std::string_view name);
[[nodiscard]] std::string_view view_name(View view);

/// A rectangle of the image in pixels (x to the right, y down).
struct PixelRect {
    double x = 0.0;
    double y = 0.0;
    double width = 0.0;
    double height = 0.0;
};

/// An orthographic camera. Image coordinates are pixels: x to the right, y down, pixel (i, j)
/// covering [i, i+1) x [j, j+1), so its centre is at (i + 0.5, j + 0.5). Depth is in world units
/// along the viewing direction: larger is farther from the viewer.
class Camera {
  public:
    /// Looks along `forward` with `up_hint` as near to up on screen as it can be (any vector not
    /// parallel to `forward`; if it is, another is picked). One world unit = one pixel, world
    /// origin at image (0, 0) until fit() or set_frame().
    [[nodiscard]] static Camera looking(const Vec3d& forward, const Vec3d& up_hint);
    [[nodiscard]] static Camera preset(View view);

    [[nodiscard]] const Vec3d& right() const { return right_; }
    [[nodiscard]] const Vec3d& up() const { return up_; }
    /// The viewing direction (unit): from the viewer into the scene.
    [[nodiscard]] const Vec3d& forward() const { return forward_; }
    /// Pixels per world unit.
    [[nodiscard]] double scale() const { return scale_; }

    /// (x, y, depth) of a world point.
    [[nodiscard]] Vec3d project(const Vec3d& p) const {
        return {origin_x_ + scale_ * p.dot(right_), origin_y_ - scale_ * p.dot(up_),
                p.dot(forward_)};
    }
    /// The world point at image position (x, y) and `depth`.
    [[nodiscard]] Vec3d unproject(double x, double y, double depth) const {
        return (x - origin_x_) / scale_ * right_ - (y - origin_y_) / scale_ * up_ +
               depth * forward_;
    }
    /// A world direction in camera coordinates: (right, up, towards the viewer).
    [[nodiscard]] Vec3d to_camera(const Vec3d& d) const {
        return {d.dot(right_), d.dot(up_), -d.dot(forward_)};
    }

    /// Sets the scale (pixels per unit, > 0) and where the world origin lands in the image.
    void set_frame(double scale, double origin_x, double origin_y);

    /// Scales and centres the camera so that the world box {right in [x_min, x_max], up in
    /// [y_min, y_max]} (coordinates along right() and up(), world units) fills `rect` less
    /// `margin` pixels on every side, keeping the aspect ratio. A box of zero size (one point) is
    /// centred, with one world unit spanning the rect.
    void fit(double x_min, double x_max, double y_min, double y_max, const PixelRect& rect,
             double margin);

  private:
    Vec3d right_ = Vec3d::UnitX();
    Vec3d up_ = Vec3d::UnitZ();
    Vec3d forward_ = Vec3d::UnitY();
    double scale_ = 1.0;
    double origin_x_ = 0.0;
    double origin_y_ = 0.0;
};

}  // namespace surfgrow::render
