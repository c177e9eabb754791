// planes.json and the bound-plane mesh (planes.ply, planes.obj): written by `surfgrow planes`
// (and `surfgrow grow`), read back by `surfgrow coverage` and by users.
#pragma once

#include <filesystem>
#include <ostream>

#include "surfgrow/io/results_io.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/planes/plane_mesh.hpp"

namespace surfgrow::io {

/// planes.json: parameters (resolved), summary, and every plane: plane equation, oriented normal,
/// centroid, in-plane axes, area, RMS, point count, bounds, member patch ids and boundary
/// polygons in plane coordinates (a, b) = centroid + a u_axis + b v_axis. Positions in file
/// coordinates (meta.offset added). Deterministic: the same planes give the same bytes.
void write_planes_json(std::ostream& out, const BoundPlanes& planes, const ResultMeta& meta);

/// Bound planes read back, positions relative to meta.offset as when computed.
struct StoredPlanes {
    BoundPlanes planes;
    ResultMeta meta;
};

/// Reads planes.json. Throws Error(kCannotOpen) if it cannot be opened and
/// Error(kMalformedInput), naming the file and the plane, for anything that is not a valid
/// planes file: not JSON, another format, a non-unit normal or axis, a ring of fewer than 3
/// vertices, a vertex that is not two finite numbers, a patch id listed twice.
[[nodiscard]] StoredPlanes read_planes_json(const std::filesystem::path& file);
/// The same for planes.json held in memory; `source` names it in messages.
[[nodiscard]] StoredPlanes parse_planes_json(std::string_view text, std::string_view source);

/// planes.ply: the triangulated polygons as a binary little-endian mesh: vertices (x, y, z;
/// double when meta.offset is non-zero), their plane's normal (nx, ny, nz) and plane id; faces
/// (vertex_indices) with their plane id. Opens in Open3D, MeshLab, CloudCompare, Blender.
void write_planes_ply(std::ostream& out, const PlaneMesh& mesh, const ResultMeta& meta);

/// planes.obj: the same mesh as Wavefront OBJ text, one object ("o plane_<id>") per plane, a
/// vertex normal per plane.
void write_planes_obj(std::ostream& out, const PlaneMesh& mesh, const ResultMeta& meta);

/// The same, meshing `planes` first (mesh_bound_planes): what `surfgrow grow` calls.
void write_planes_ply(std::ostream& out, const BoundPlanes& planes, const ResultMeta& meta);
void write_planes_obj(std::ostream& out, const BoundPlanes& planes, const ResultMeta& meta);

/// Reads a planes.ply written by write_planes_ply (positions relative to `offset`, which is
/// subtracted). Throws Error(kCannotOpen) or Error(kMalformedInput) naming the file and the
/// problem (another layout, truncated, an index out of range).
[[nodiscard]] PlaneMesh read_planes_ply(const std::filesystem::path& file,
                                        const Vec3d& offset = Vec3d::Zero());
/// The same for planes.ply held in memory; `source` names it in messages.
[[nodiscard]] PlaneMesh parse_planes_ply(std::string_view bytes, std::string_view source,
                                         const Vec3d& offset = Vec3d::Zero());

}  // namespace surfgrow::io
