// Small geometric value types shared by every module.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace surfgrow {

using Vec3f = Eigen::Vector3f;
using Vec3d = Eigen::Vector3d;
using Mat3d = Eigen::Matrix3d;

/// Axis-aligned box; empty() until a point is added.
struct Aabb {
    Vec3d min = Vec3d::Constant(std::numeric_limits<double>::infinity());
    Vec3d max = Vec3d::Constant(-std::numeric_limits<double>::infinity());

    void add(const Vec3d& p) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
    [[nodiscard]] bool empty() const { return !(min.x() <= max.x()); }
    [[nodiscard]] bool contains(const Vec3d& p) const {
        return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
    }
    [[nodiscard]] Vec3d size() const { return empty() ? Vec3d::Zero() : Vec3d(max - min); }
    [[nodiscard]] Vec3d center() const { return 0.5 * (min + max); }
};

/// Plane n.x + d = 0 with unit normal n.
struct Plane {
    Vec3d normal = Vec3d::UnitZ();
    double d = 0.0;

    static Plane through(const Vec3d& point, const Vec3d& unit_normal) {
        return {unit_normal, -unit_normal.dot(point)};
    }
    [[nodiscard]] double signed_distance(const Vec3d& p) const { return normal.dot(p) + d; }
};

[[nodiscard]] inline bool is_finite(const Vec3f& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

/// Angle between two vectors in radians, in [0, pi]. atan2 of the cross and dot products keeps
/// full precision at small angles, where acos(dot) resolves only ~1e-8 rad.
[[nodiscard]] inline double angle_between(const Vec3d& a, const Vec3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Angle between two unoriented directions (lines), in [0, pi/2].
[[nodiscard]] inline double axis_angle_between(const Vec3d& a, const Vec3d& b) {
    return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

}  // namespace surfgrow
