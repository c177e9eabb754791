// The shapes of collision queries: spheres and capsules, and the exact distances between them.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// A ball: every point within `radius` of `centre`.
struct Sphere {
    Vec3d centre = Vec3d::Zero();
    double radius = 0.0;
};

/// A capsule: every point within `radius` of the segment [a, b]. With a == b it is a sphere.
struct Capsule {
    Vec3d a = Vec3d::Zero();
    Vec3d b = Vec3d::Zero();
    double radius = 0.0;

    [[nodiscard]] static Capsule of(const Sphere& s) { return {s.centre, s.centre, s.radius}; }
};

/// Whether every coordinate is finite and the radius is finite and >= 0.
[[nodiscard]] inline bool is_valid(const Sphere& s) {
    return s.centre.allFinite() && std::isfinite(s.radius) && s.radius >= 0;
}
[[nodiscard]] inline bool is_valid(const Capsule& c) {
    return c.a.allFinite() && c.b.allFinite() && std::isfinite(c.radius) && c.radius >= 0;
}

/// Exact distance from p to the segment [a, b] (a == b allowed).
[[nodiscard]] inline double point_segment_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
    const Vec3d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

/// Signed clearance between an environment sphere and a capsule: the distance between their
/// surfaces, negative when they overlap (by the penetration depth along the closest line).
[[nodiscard]] inline double clearance(const Sphere& s, const Capsule& c) {
    return point_segment_distance(s.centre, c.a, c.b) - s.radius - c.radius;
}

/// No environment: the clearance of a query against nothing.
inline constexpr double kNoClearanceLimit = std::numeric_limits<double>::infinity();

}  // namespace surfgrow
