// Bound planes as one triangle mesh: each plane's boundary polygons, triangulated with holes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/planes/bound_planes.hpp"

namespace surfgrow {

/// Triangles of all planes. Every vertex belongs to one plane; triangles wind counter-clockwise
/// seen from the plane's normal (its sensor side).
struct PlaneMesh {
    std::vector<Vec3d> vertices;              ///< cloud frame (relative to offset)
    std::vector<std::uint32_t> vertex_plane;  ///< per vertex: its plane
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint32_t> triangle_plane;  ///< per triangle: its plane
    std::vector<Vec3d> plane_normals;           ///< per plane
};

/// Triangulates every polygon of every plane (triangulate()) and lifts it into 3D.
[[nodiscard]] PlaneMesh mesh_bound_planes(const BoundPlanes& planes);

}  // namespace surfgrow
