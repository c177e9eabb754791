// The occupancy grid as an OctoMap (.bt) with free space carved by rays from the scan origins.
#pragma once

#include <cstdint>
#include <memory>
#include <ostream>
#include <span>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"
#include "surfgrow/robot/sensor_origins.hpp"

namespace surfgrow::io {

/// What went into an OctoMap export.
struct OctomapSummary {
    double resolution = 0.0;     ///< OctoMap's leaf size: mu
    std::uint64_t occupied = 0;  ///< occupied leaves at full depth (= the grid's occupied cubes)
    std::uint64_t free = 0;      ///< free leaves at full depth, carved by rays
    std::uint64_t rays = 0;      ///< rays cast (one per sensor origin and end cell)
    SensorOrigins::Source carving = SensorOrigins::Source::kNone;
};

/// Writes the occupancy as an OctoMap OcTree at resolution grid.mu() in OctoMap's binary .bt
/// format: the bytes of OcTree::writeBinary (maximum-likelihood occupied / free, pruned, unknown
/// where there is no node), written from the leaves' keys (write_octree_binary).
///
/// Coordinates are the cloud's own frame (PointCloud positions, i.e. file coordinates minus
/// cloud.offset, which is zero for all but georeferenced clouds).
///
/// Occupied: each occupied cube of `grid` becomes the OctoMap leaf holding the cube's centre.
/// OctoMap's keys are aligned on the frame origin (leaf k covers [k mu, (k + 1) mu)) while the
/// grid is aligned on the grower's index; since the grid's side is mu (1 + 2^-20) >= mu,
/// distinct cubes always land in distinct leaves, so the occupied leaves are exactly as many as
/// the occupied cubes and each lies within half a leaf of its cube.
///
/// Free: for every point with `ray_mask` set (or every finite point when it is empty) whose
/// origin is known, the leaves on the ray from its sensor origin to the centre of the leaf it
/// ends in (OctoMap's computeRayKeys, end leaf excluded; one ray per origin and end leaf, as
/// OctoMap's discretized insertion), less the occupied leaves and every leaf a ray ends in.
/// Occupied therefore always wins: grazing rays never erode a surface, and end leaves that are
/// not occupied (noise, unregistered points) stay unknown. Without origins nothing is free.
///
/// Throws Error(kCloudTooLarge) when a cell or origin lies beyond OctoMap's key range (2^15
/// leaves, 393 m at 12 mm, each way from the frame origin) and Error(kCannotWrite) if the stream
/// fails. Deterministic: the same bytes for the same input, for any number of `threads` (rays
/// are cast in parallel; 0: every core).
OctomapSummary write_octomap_bt(std::ostream& out, const OccupancyGrid& grid,
                                const CloudView& cloud, std::span<const std::uint8_t> ray_mask,
                                const SensorOrigins& origins, int threads = 1);

/// write_octomap_bt for a cloud that only grows, as `surfgrow map`'s after each scan: each
/// write() casts only the rays of the points added since the previous one (the free leaves
/// are a union of rays, whatever the order they are cast in), keeps what they carved, and
/// writes the same bytes as write_octomap_bt on the whole cloud. The carved leaves stay in a
/// bitmap over the box of the rays so far (moved to a larger one when a scan reaches past it).
///
/// Contract: each call's cloud is the previous one's with points appended, the same mask for
/// those points, and the same first origins. A cloud that shrank or origins that changed start
/// it afresh (correct, not incremental); changed points in place are not detected.
class OctomapCarver {
  public:
    OctomapCarver();
    ~OctomapCarver();
    OctomapCarver(OctomapCarver&&) noexcept;
    OctomapCarver& operator=(OctomapCarver&&) noexcept;

    /// As write_octomap_bt. The rays are kept for the grid's resolution (another starts afresh).
    OctomapSummary write(std::ostream& out, const OccupancyGrid& grid, const CloudView& cloud,
                         std::span<const std::uint8_t> ray_mask, const SensorOrigins& origins,
                         int threads = 1);

  private:
    struct State;
    std::unique_ptr<State> state_;
    bool keep_ = true;  // false: one write only, which may spend the carved bits
    friend OctomapSummary write_octomap_bt(std::ostream&, const OccupancyGrid&, const CloudView&,
                                           std::span<const std::uint8_t>, const SensorOrigins&,
                                           int);
};

}  // namespace surfgrow::io
