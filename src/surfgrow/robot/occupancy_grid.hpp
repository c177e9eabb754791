// The 3D occupancy grid of paper sections 4 and 5.5: the grower's cubes that hold registered
// points.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/grown_points.hpp"

namespace surfgrow {

/// Integer coordinates of a cube: cube c covers origin + [c, c + 1) * cube_size on each axis.
using CellCoords = Eigen::Vector3i;

/// The cubes of side mu that hold at least one registered point, on exactly the grid of the
/// grower's cube index (paper 4.1): same origin, same side, same float rounding of positions.
///
/// The side is cube_size() = mu enlarged by one part in 2^20 (see CubeIndex) and the origin is the
/// low corner of the grown points' bounding box less one and a half cubes, so the grid depends on
/// the data; both are stated in every output. Only occupied cubes are stored (sorted by x, then y,
/// then z): memory is O(occupied cubes) whatever the extent.
class OccupancyGrid {
  public:
    /// An empty grid (nothing occupied) with side `mu`.
    explicit OccupancyGrid(double mu = 0.0) : mu_(mu) {}

    /// The cubes of `index` holding a point whose label is >= 0; `labels` has one entry per input
    /// point (the index's original indices refer to it). `mu` is the side the index was asked for.
    OccupancyGrid(const CubeIndex& index, std::span<const std::int32_t> labels, double mu);

    [[nodiscard]] double mu() const { return mu_; }
    /// The side actually used: mu * (1 + 2^-20), as in the grower's index.
    [[nodiscard]] double cube_size() const { return cube_size_; }
    /// World position (the cloud's frame) of the low corner of cube (0, 0, 0).
    [[nodiscard]] const Vec3d& origin() const { return origin_; }

    [[nodiscard]] std::size_t size() const { return cells_.size(); }
    [[nodiscard]] bool empty() const { return cells_.empty(); }
    /// Occupied cubes, sorted by (x, y, z).
    [[nodiscard]] std::span<const CellCoords> cells() const { return cells_; }
    /// Registered points in each occupied cube, parallel to cells().
    [[nodiscard]] std::span<const std::uint32_t> point_counts() const { return counts_; }
    [[nodiscard]] std::uint64_t registered_points() const { return registered_; }

    /// Centre of cube `c` (world).
    [[nodiscard]] Vec3d centre(const CellCoords& c) const {
        return origin_ + (c.cast<double>() + Vec3d::Constant(0.5)) * cube_size_;
    }
    /// The cube a world position falls in, with the index's float rounding: every registered
    /// point lies in an occupied cube.
    [[nodiscard]] CellCoords cell_of(const Vec3d& p) const;
    /// Whether cube `c` is occupied (binary search).
    [[nodiscard]] bool occupied_cell(const CellCoords& c) const;
    /// Whether the cube holding world position `p` is occupied. False for NaN.
    [[nodiscard]] bool occupied(const Vec3d& p) const;
    /// Union of the occupied cubes (world); empty if none.
    [[nodiscard]] Aabb bounds() const;

    /// Counts one more registered point in each of `cells` (cell_of of the point), occupying
    /// the cubes not yet occupied: the grid of the cloud with those points added, as long as they
    /// leave the index's origin where it is (OccupancyMemo checks that).
    void add_registered(std::vector<CellCoords> cells);

  private:
    double mu_ = 0.0;
    double cube_size_ = 0.0;
    double inv_cube_ = 0.0;
    Vec3d origin_ = Vec3d::Zero();
    std::vector<CellCoords> cells_;
    std::vector<std::uint32_t> counts_;
    std::uint64_t registered_ = 0;
};

/// The occupancy grid of a grow result: the grower's cube index over the grown points of `cloud`
/// (side config.mu), keeping the cubes with a registered point (labels >= 0).
///
/// Throws Error(kInvalidParameter) if `labels` does not have one entry per point, or if a
/// labelled point is not a grown point (the labels or the configuration are not those of this
/// cloud), and the index's errors (kInvalidParameter, kCloudTooLarge).
[[nodiscard]] OccupancyGrid occupancy_grid(const CloudView& cloud,
                                           std::span<const std::int32_t> labels,
                                           const GrowerConfig& config);

/// Same, from the result of grow_surfaces(cloud, config).
[[nodiscard]] inline OccupancyGrid occupancy_grid(const CloudView& cloud, const GrowResult& result,
                                                  const GrowerConfig& config) {
    return occupancy_grid(cloud, result.labels, config);
}

}  // namespace surfgrow
