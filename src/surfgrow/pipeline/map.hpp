// Mapping while scanning (paper section 5.4: each scan processed while the next is taken): scans
// added one at a time to one map, whose surfaces and robot outputs are ready after each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/pipeline/pipeline.hpp"

namespace surfgrow {

struct MapConfig {
    PipelineConfig pipeline;
    /// A new point joins an existing surface when it lies within the surface's neighbourhood
    /// (radius) of its home point and within this many times the surface's own tolerance of its
    /// plane; the nearest such plane, relative to its tolerance, takes it. Above 1: a scan's
    /// layer of a surface lies a little off another's (the sensor's systematic error).
    double join_tolerance = 1.5;
};

/// What one add_scan did, and how long each part took (seconds, not part of the result).
struct MapUpdate {
    std::size_t scan = 0;            ///< the scan's number, from 0
    std::uint64_t points = 0;        ///< its points
    std::uint64_t joined = 0;        ///< of them, joined to surfaces of earlier scans
    std::uint64_t grown = 0;         ///< registered to surfaces grown from its other points
    std::uint64_t new_surfaces = 0;  ///< surfaces grown from it
    double join_seconds = 0.0;
    double grow_seconds = 0.0;
    double outputs_seconds = 0.0;  ///< the robot outputs of the whole map
};

/// A map grown scan by scan. add_scan(k) costs the growing of scan k alone plus the robot
/// outputs of the map; its points either join surfaces already there or grow new ones, so
/// nothing grown before is grown again. The result is deterministic for a given order of scans,
/// configuration and seed (scan k grows from seed mix_seed(seed, k)), for any number of threads.
///
/// Differences from growing the fused cloud at once (the bounds the tests hold it to are in
/// docs/scanner.md, "Mapping while scanning"): a surface is fitted to the scan that first saw
/// it, and a point an earlier scan left unregistered stays so.
class Map {
  public:
    /// Throws Error(kInvalidParameter) for an invalid configuration or join_tolerance outside
    /// [1, 10].
    explicit Map(MapConfig config);

    /// Adds one scan: its points in the map's frame and units (offset added if it differs from
    /// the first scan's), taken from `origin` (relative to the scan's offset). Its labels (ground
    /// truth) are kept when every scan has them. Returns the map's result after it.
    const PipelineResult& add_scan(const CloudView& scan, const Vec3d& origin);

    [[nodiscard]] const PipelineResult& result() const { return result_; }
    /// Every point so far, scan by scan, with its scan index and the scans' origins: the cloud
    /// the result's labels index (the same as fusing the scans in the same order).
    [[nodiscard]] const PointCloud& cloud() const { return cloud_; }
    [[nodiscard]] std::size_t scans() const { return cloud_.scan_origins.size(); }
    [[nodiscard]] const MapUpdate& last_update() const { return last_; }
    [[nodiscard]] const MapConfig& config() const { return config_; }
    /// The pipeline's configuration as it runs (Pipeline::config).
    [[nodiscard]] const PipelineConfig& pipeline_config() const { return pipeline_.config(); }

  private:
    void index_surfaces(std::size_t from);
    [[nodiscard]] std::int64_t cell_key(const Vec3d& p) const;

    MapConfig config_;
    Pipeline pipeline_;
    PointCloud cloud_;
    PipelineResult result_;
    MapUpdate last_;
    bool labelled_ = true;
    double cell_ = 1.0;  // side of the surface lookup's cells
    std::unordered_map<std::int64_t, std::vector<std::int32_t>> cells_;
    PipelineMemo memo_;  // surfaces only gain points here: the outputs reuse what they left
};

}  // namespace surfgrow
