// Planar polygons with holes, in a plane's own 2D coordinates.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <span>
#include <vector>

namespace surfgrow {

using Vec2d = Eigen::Vector2d;

/// A closed ring of vertices (the last joins the first; no vertex is repeated).
using Ring = std::vector<Vec2d>;

/// One connected piece of a region: its outer ring counter-clockwise, its holes clockwise.
struct PolygonWithHoles {
    Ring outer;
    std::vector<Ring> holes;
};

/// Signed area of a ring: positive when counter-clockwise (shoelace formula).
[[nodiscard]] inline double signed_area(std::span<const Vec2d> ring) {
    const std::size_t n = ring.size();
    if (n < 3) return 0.0;
    double twice = 0.0;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
        twice += (ring[j].x() - ring[i].x()) * (ring[j].y() + ring[i].y());
    return 0.5 * twice;
}

/// Area of a polygon: its outer ring less its holes, whatever their orientation.
[[nodiscard]] inline double polygon_area(const PolygonWithHoles& p) {
    double a = std::abs(signed_area(p.outer));
    for (const Ring& h : p.holes) a -= std::abs(signed_area(h));
    return a;
}

/// True when q lies inside the ring (even-odd rule; points on an edge may go either way).
[[nodiscard]] inline bool ring_contains(std::span<const Vec2d> ring, const Vec2d& q) {
    bool inside = false;
    const std::size_t n = ring.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2d& a = ring[i];
        const Vec2d& b = ring[j];
        if ((a.y() > q.y()) != (b.y() > q.y()) &&
            q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
            inside = !inside;
    }
    return inside;
}

/// True when q lies inside the polygon: inside its outer ring and in none of its holes.
[[nodiscard]] inline bool polygon_contains(const PolygonWithHoles& p, const Vec2d& q) {
    if (!ring_contains(p.outer, q)) return false;
    for (const Ring& h : p.holes)
        if (ring_contains(h, q)) return false;
    return true;
}

/// z of the cross product (b - a) x (c - a): positive when a, b, c turn counter-clockwise.
[[nodiscard]] inline double orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace surfgrow
