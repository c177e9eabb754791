#include "surfgrow/render/camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::render {

View parse_view(std::string_view name) {
    if (name == "front") return View::kFront;
    if (name == "side") return View::kSide;
    if (name == "top") return View::kTop;
    if (name == "iso") return View::kIso;
    throw Error(ErrorCode::kInvalidParameter,
                cat({"unknown view '", name, "' (expected front, side, top or iso)"}));
}

std::string_view view_name(View view) {
    switch (view) {
        case View::kFront:
            return "front";
        case View::kSide:
            return "side";
        case View::kTop:
            return "top";
        case View::kIso:
            return "iso";
    }
    return "iso";
}

Camera Camera::looking(const Vec3d& forward, const Vec3d& up_hint) {
    const double len = forward.norm();
    if (!(len > 0) || !std::isfinite(len))
        throw Error(ErrorCode::kInvalidParameter,
                    "camera direction must be a finite non-zero vector");
    Camera c;
    c.forward_ = forward / len;
    Vec3d right = c.forward_.cross(up_hint);
    if (right.norm() < 1e-9) right = c.forward_.cross(Vec3d::UnitY());
    if (right.norm() < 1e-9) right = c.forward_.cross(Vec3d::UnitX());
    c.right_ = right.normalized();
    c.up_ = c.right_.cross(c.forward_).normalized();
    return c;
}

Camera Camera::preset(View view) {
    switch (view) {
        case View::kFront:
            return looking(Vec3d::UnitY(), Vec3d::UnitZ());
        case View::kSide:
            return looking(-Vec3d::UnitX(), Vec3d::UnitZ());
        case View::kTop:
            return looking(-Vec3d::UnitZ(), Vec3d::UnitY());
        case View::kIso:
            return looking(Vec3d(-1, 1, -1), Vec3d::UnitZ());
    }
    return looking(Vec3d(-1, 1, -1), Vec3d::UnitZ());
}

void Camera::set_frame(double scale, double origin_x, double origin_y) {
    if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(origin_x) ||
        !std::isfinite(origin_y))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"camera scale must be positive and finite, got ", num(scale)}));
    scale_ = scale;
    origin_x_ = origin_x;
    origin_y_ = origin_y;
}

void Camera::fit(double x_min, double x_max, double y_min, double y_max, const PixelRect& rect,
                 double margin) {
    const double avail_w = std::max(rect.width - 2 * margin, 1.0);
    const double avail_h = std::max(rect.height - 2 * margin, 1.0);
    const double w = x_max - x_min, h = y_max - y_min;
    double scale = std::min(w > 0 ? avail_w / w : HUGE_VAL, h > 0 ? avail_h / h : HUGE_VAL);
    if (!std::isfinite(scale) || !(scale > 0)) scale = std::min(avail_w, avail_h);  // one point
    const double cx = rect.x + rect.width / 2, cy = rect.y + rect.height / 2;
    set_frame(scale, cx - scale * (x_min + x_max) / 2, cy + scale * (y_min + y_max) / 2);
}

}  // namespace surfgrow::render
