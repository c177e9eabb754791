// The robot outputs of a grow result, staged into an output folder: `surfgrow grow` and the
// `occupancy` subcommand call these.
#pragma once

#include <cstdint>
#include <span>

#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/occupancy_grid.hpp"
#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/octomap_export.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::io {

struct OccupancyOutputs {
    bool ply = true;      ///< occupancy.ply
    bool octomap = true;  ///< environment.bt
    bool json = true;     ///< occupancy.json
};

struct OccupancySummary {
    std::uint64_t occupied_cubes = 0;
    std::uint64_t registered_points = 0;
    bool octomap_written = false;
    OctomapSummary octomap;
};

/// Computes the occupancy grid of (cloud, labels, config) and stages occupancy.ply,
/// environment.bt and occupancy.json into `tx` (see occupancy_io.hpp and octomap_export.hpp).
/// Rays are cast to the grown points (finite, inside the crop) from sensor_origins(cloud, config).
/// Throws what occupancy_grid() and write_octomap_bt() throw.
OccupancySummary add_occupancy_outputs(OutputTransaction& tx, const PointCloud& cloud,
                                       std::span<const std::int32_t> labels,
                                       const GrowerConfig& config, const ResultMeta& meta,
                                       const OccupancyOutputs& which = {});

/// Same for the result of grow_surfaces(cloud, config).
inline OccupancySummary add_occupancy_outputs(OutputTransaction& tx, const PointCloud& cloud,
                                              const GrowResult& result, const GrowerConfig& config,
                                              const ResultMeta& meta,
                                              const OccupancyOutputs& which = {}) {
    return add_occupancy_outputs(tx, cloud, result.labels, config, meta, which);
}

/// Stages collision_spheres.json: one sphere per surface at its home point, radius mu.
void add_collision_outputs(OutputTransaction& tx, const GrowResult& result, const ResultMeta& meta);

}  // namespace surfgrow::io
