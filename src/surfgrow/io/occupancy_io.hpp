// occupancy.ply and occupancy.json: the occupancy grid for viewers, planners and scripts.
#pragma once

#include <ostream>

#include "surfgrow/io/octomap_export.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"

namespace surfgrow::io {

/// occupancy.ply: one vertex per occupied cube at its centre, with `count` (registered points in
/// the cube). Binary little-endian; positions in double when the cloud had an offset, float
/// otherwise. The header's comments state the units, mu, the cube side and the grid origin.
void write_occupancy_ply(std::ostream& out, const OccupancyGrid& grid, const ResultMeta& meta);

/// occupancy.json: units, mu, cube side, origin (file coordinates), the cell convention, counts,
/// bounds, and, when `octomap` is given, what environment.bt holds (resolution, frame, occupied
/// and free leaves, rays and where they came from). Deterministic: no timings.
void write_occupancy_json(std::ostream& out, const OccupancyGrid& grid, const ResultMeta& meta,
                          const OctomapSummary* octomap);

}  // namespace surfgrow::io
