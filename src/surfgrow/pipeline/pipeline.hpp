// The whole job of surfgrow on one cloud, as a library call: grow the surfaces, bind them into
// planes, plan coverage over the planes, build the occupancy grid and the collision spheres.
#pragma once

#include <optional>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/planes/bound_plane_memo.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/coverage.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"
#include "surfgrow/robot/occupancy_memo.hpp"

namespace surfgrow {

/// What to compute, from one configuration. Lengths are in the cloud's units. Every stage is on
/// by default: the result holds everything a planner needs.
struct PipelineConfig {
    GrowerConfig grow;
    /// Bound planes; their mu and threads are the grower's (the values here are ignored).
    std::optional<BoundPlaneConfig> planes = BoundPlaneConfig{};
    /// Coverage goals and tool path over the bound planes (only when planes are computed); its
    /// threads are the grower's.
    std::optional<CoverageConfig> coverage = CoverageConfig{};
    bool occupancy = true;  ///< the occupancy grid, on the grower's own cube index
    bool collision = true;  ///< one collision sphere per surface
};

/// Wall-clock seconds of each stage (0 for a stage not run).
struct PipelineSeconds {
    double planes = 0.0;
    double coverage = 0.0;
    double occupancy = 0.0;
    double collision = 0.0;
    // The growing's own stages are in GrowResult::stats.seconds.
};

/// Everything one run computed; a stage that was not asked for is empty.
struct PipelineResult {
    GrowResult grow;
    std::optional<BoundPlanes> planes;
    std::optional<CoveragePlan> coverage;
    std::optional<OccupancyGrid> occupancy;
    std::optional<CollisionSpheres> collision;
    PipelineSeconds seconds;
};

/// What a Pipeline keeps from one finish() to the next on a map, whose surfaces only gain points
/// and whose cloud only gains points at its end (Map): the work of the bound planes, coverage and
/// occupancy grid that the new points left as it was.
struct PipelineMemo {
    BoundPlaneMemo planes;
    CoverageMemo coverage;
    OccupancyMemo occupancy;
};

/// Runs the stages of a PipelineConfig over clouds. The result is the same, byte for byte, for
/// any number of threads, and the same as calling the stages one by one.
class Pipeline {
  public:
    /// Throws Error(kInvalidParameter) if any stage's configuration is out of range.
    explicit Pipeline(PipelineConfig config);

    /// The configuration, with the planes' and coverage's mu and threads taken from the grower.
    [[nodiscard]] const PipelineConfig& config() const { return config_; }

    /// Runs every configured stage over `cloud`. GrowerConfig::progress hears the grower's stages,
    /// then "planes", "coverage", "occupancy", "collision" as each ends, and "done".
    [[nodiscard]] PipelineResult run(const CloudView& cloud) const;

    /// Runs the stages after growing over a result grown elsewhere (a Map's): `grown` holds
    /// surfaces and one label per point of `cloud`. Throws Error(kInvalidParameter) when the
    /// labels do not match the cloud. A `memo` carries work from one call to the next where the
    /// surfaces only gained points (PipelineMemo), in less time: the same result, except that a
    /// bound plane whose region changed has its boundary traced on the cell counts the memo kept
    /// (within a raster cell of the one traced anew; compute_bound_planes) and coverage follows.
    [[nodiscard]] PipelineResult finish(const CloudView& cloud, const GrowResult& grown,
                                        PipelineMemo* memo = nullptr) const;
    /// The same, taking `grown` over once every stage has run (a map's millions of labels are
    /// not copied); if a stage throws, `grown` is left as it was.
    [[nodiscard]] PipelineResult finish(const CloudView& cloud, GrowResult&& grown,
                                        PipelineMemo* memo = nullptr) const;

  private:
    PipelineResult outputs(const CloudView& cloud, GrowResult&& grown,
                           std::optional<GrowIndex> index, PipelineMemo* memo) const;

    PipelineConfig config_;
};

/// One-call helper: Pipeline(config).run(cloud).
[[nodiscard]] inline PipelineResult run_pipeline(const CloudView& cloud,
                                                 const PipelineConfig& config = {}) {
    return Pipeline(config).run(cloud);
}

}  // namespace surfgrow
