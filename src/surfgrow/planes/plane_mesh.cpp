#include "surfgrow/planes/plane_mesh.hpp"

#include "surfgrow/planes/polygon_triangulation.hpp"

namespace surfgrow {

PlaneMesh mesh_bound_planes(const BoundPlanes& planes) {
    PlaneMesh mesh;
    for (std::size_t p = 0; p < planes.planes.size(); ++p) {
        const BoundPlane& bp = planes.planes[p];
        const auto id = static_cast<std::uint32_t>(p);
        mesh.plane_normals.push_back(bp.normal);
        for (const PolygonWithHoles& poly : bp.polygons) {
            const Triangulation t = triangulate(poly);
            const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
            for (const Vec2d& q : t.vertices) {
                mesh.vertices.push_back(bp.to_world(q));
                mesh.vertex_plane.push_back(id);
            }
            for (const auto& tri : t.triangles) {
                mesh.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
                mesh.triangle_plane.push_back(id);
            }
        }
    }
    return mesh;
}

}  // namespace surfgrow
