// What a map's occupancy grid keeps from one update to the next (pipeline/map.hpp): the map's
// cloud only gains points, at its end, and its earlier points keep their labels. While the new
// points leave the grown points' low corner (the grid's origin) where it was, the grid is the old
// one plus a point in each new registered point's cube: the same grid as indexing the whole cloud
// anew, without indexing the whole cloud.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"

namespace surfgrow {

/// The grid of a cloud's first `points` points (its mu is the grid's), and what decides whether a
/// later cloud extends it.
struct OccupancyMemo {
    std::size_t points = 0;        ///< the cloud's first points it covers (0: none)
    Aabb grown_box;                ///< of their grown points (the index's bounds)
    std::uint64_t registered = 0;  ///< of them, labelled >= 0
    Vec3f last = Vec3f::Zero();    ///< the last covered point and its label, a spot check
    std::int32_t last_label = -1;
    WorkspaceCrop crop;
    Vec3d crop_centre = Vec3d::Zero();
    std::optional<OccupancyGrid> grid;
};

/// The occupancy grid of (cloud, labels) from the memo's, where the memo covers a prefix of this
/// cloud (the same count of registered points and the same last point and label there, the same
/// mu and crop) and the points after it leave the low corner of the grown points' box as it was.
/// Updates the memo to the whole cloud and returns the grid; nullopt (memo untouched) otherwise:
/// the caller indexes the cloud and calls remember_occupancy.
[[nodiscard]] std::optional<OccupancyGrid> extend_occupancy(OccupancyMemo& memo,
                                                            const CloudView& cloud,
                                                            std::span<const std::int32_t> labels,
                                                            const GrowerConfig& config);

/// Makes `grid`, built on a cube index of the whole cloud whose bounds are `grown_box`, the
/// memo's.
void remember_occupancy(OccupancyMemo& memo, const CloudView& cloud,
                        std::span<const std::int32_t> labels, const Aabb& grown_box,
                        const OccupancyGrid& grid, const GrowerConfig& config);

}  // namespace surfgrow
