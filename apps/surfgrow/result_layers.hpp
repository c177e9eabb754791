// The optional layers of a result folder: bound planes (planes.json) and the coverage path
// (coverage.json). Both files come from other commands; this is the one place that reads them,
// so a change of their format is a change here only (docs/viewer.md, "Optional layers").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::cli {

/// One connected piece of a bound plane (planes.json) in the result's frame, for drawing.
struct PlaneOutline {
    std::int32_t id = -1;
    Vec3d normal = Vec3d::UnitZ();
    std::vector<Vec3d> boundary;            ///< outer polygon, in order, not closed (>= 3)
    std::vector<std::vector<Vec3d>> holes;  ///< inner polygons (may be empty)
    std::vector<std::int32_t> surfaces;     ///< indices into surfaces.json
};

/// The coverage path: the goals a tool visits, in order.
struct CoveragePath {
    std::vector<Vec3d> goals;
};

/// What the folder holds beyond surfaces.json. Positions are in the result's frame (file
/// coordinates minus meta.offset), like io::StoredResult's.
struct ResultLayers {
    std::optional<std::vector<PlaneOutline>> planes;  ///< nullopt: no planes.json
    std::optional<CoveragePath> coverage;             ///< nullopt: no coverage.json
};

/// Reads dir/planes.json and dir/coverage.json where they exist. Throws Error(kMalformedInput)
/// naming the file and the problem when one is not valid (wrong units, a surface id the result
/// does not have, a polygon of fewer than 3 vertices, non-finite numbers).
[[nodiscard]] ResultLayers read_result_layers(const std::filesystem::path& dir,
                                              const io::StoredResult& result);

/// Only dir/planes.json, as read_result_layers() reads it (the pictures colour by plane without
/// parsing a coverage.json of tens of MB).
[[nodiscard]] std::optional<std::vector<PlaneOutline>> read_plane_outlines(
    const std::filesystem::path& dir, const io::StoredResult& result);

/// For each of `surface_count` surfaces, the id of the bound plane that lists it (-1: none; the
/// first plane listing it wins).
[[nodiscard]] std::vector<std::int32_t> plane_of_surface(const std::vector<PlaneOutline>& planes,
                                                         std::size_t surface_count);

}  // namespace surfgrow::cli
