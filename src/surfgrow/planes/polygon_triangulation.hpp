// Triangulating a polygon with holes by ear clipping, for meshes of bound planes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "surfgrow/planes/polygon2d.hpp"

namespace surfgrow {

/// Triangles over a polygon's vertices: `vertices` is the outer ring followed by each hole in
/// order, and every triangle indexes into it, counter-clockwise.
struct Triangulation {
    std::vector<Vec2d> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Ear clipping with holes (each hole bridged to the outer ring from its rightmost vertex,
/// after D. Eberly, "Triangulation by Ear Clipping"). A simple polygon with h holes and n vertices
/// in all gives n + 2h - 2 triangles whose areas add up to polygon_area(). Never fails: where the
/// input is not simple (a hole outside its ring, crossing edges after simplification) it still
/// returns triangles over the vertices, skipping degenerate ones. O(n^2).
[[nodiscard]] Triangulation triangulate(const PolygonWithHoles& polygon);

}  // namespace surfgrow
