// The files of a result folder, staged from a result in memory into one output transaction:
// `surfgrow grow` stages a whole pipeline result, the subcommands the parts they redo.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/octomap_export.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/pipeline/pipeline.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/coverage.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"

namespace surfgrow::io {

/// Which files to write besides surfaces.ply and surfaces.json. The robot outputs' files are
/// written when the result holds them.
struct ResultFiles {
    bool labels = true;         ///< labels.bin
    bool labels_txt = false;    ///< labels.txt besides (or, without labels, instead of) labels.bin
    bool csv = false;           ///< surfaces.csv
    bool planes_obj = false;    ///< planes.obj besides planes.json and planes.ply
    bool coverage_csv = false;  ///< coverage.csv besides coverage.json and coverage.ply
    bool occupancy = true;      ///< occupancy.ply and occupancy.json
    bool octomap = true;        ///< environment.bt (free space carved from the scan origins)
};

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
    double octomap_seconds = 0.0;  ///< casting its rays and writing it (in memory)
};

/// Whether `file_name` is one of the files a result folder can hold (those below, surfaces.png,
/// run.json, eval.json, collision.json): a new `surfgrow grow` into the folder replaces them all,
/// written again or not, so no output of an earlier run survives beside the new result.
[[nodiscard]] bool is_result_file(std::string_view file_name);

/// Stages the files of `result`, computed over `cloud` by a Pipeline with `config`: surfaces.ply,
/// surfaces.json and, as `files` and the result have them, labels.bin/.txt, surfaces.csv, planes.*,
/// coverage.*, occupancy.*, environment.bt, collision_spheres.*. Returns what the occupancy
/// outputs found (zero when there is no grid).
/// `meanwhile` (the caller's own files, e.g. the pictures) runs while environment.bt's rays are
/// cast on another thread, before the other files are staged. With a `carver` (a map refreshed
/// after each scan), environment.bt casts only the rays of the points added since its last use.
OccupancySummary stage_result(OutputTransaction& tx, const CloudView& cloud,
                              const PipelineConfig& config, const PipelineResult& result,
                              const ResultMeta& meta, const ResultFiles& files = {},
                              const std::function<void()>& meanwhile = {},
                              OctomapCarver* carver = nullptr);

/// Stages planes.json, planes.ply and, with `obj`, planes.obj; drops what the new planes make
/// stale (planes.obj without `obj`, coverage.*, eval.json) unless staged again.
void stage_planes(OutputTransaction& tx, const BoundPlanes& planes, const ResultMeta& meta,
                  bool obj);

/// Stages coverage.json, coverage.ply and, with `csv`, coverage.csv (else drops an old one).
void stage_coverage(OutputTransaction& tx, const CoveragePlan& plan, const ResultMeta& meta,
                    bool csv = false);

/// Stages occupancy.ply, environment.bt and occupancy.json for `grid`, the occupancy grid of
/// (cloud, config) (see occupancy_io.hpp and octomap_export.hpp). The OctoMap's rays are cast to
/// the grown points (finite, inside the crop) from sensor_origins(cloud, config). Drops the
/// occupancy files `which` leaves out (they described another grid). Throws what
/// write_octomap_bt() throws.
OccupancySummary stage_occupancy(OutputTransaction& tx, const OccupancyGrid& grid,
                                 const CloudView& cloud, const GrowerConfig& config,
                                 const ResultMeta& meta, const OccupancyOutputs& which = {});

/// Stages collision_spheres.json and collision_spheres.ply.
void stage_collision(OutputTransaction& tx, const CollisionSpheres& spheres,
                     const ResultMeta& meta);

}  // namespace surfgrow::io
