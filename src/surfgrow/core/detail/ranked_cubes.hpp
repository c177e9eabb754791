// The cube index's layout for a cloud too wide for packed grid keys: occupied cube coordinates
// ranked, so that any finite extent fits a 63-bit key.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace surfgrow::detail {

/// The distinct occupied grid coordinates of one axis and their ranks.
///
/// Coordinates g_0 < g_1 < ... get ranks r_0 = 1 and r_i = r_(i-1) + 1 where g_i = g_(i-1) + 1,
/// else r_(i-1) + 2: neighbouring cubes keep neighbouring ranks, and any run of empty coordinates
/// becomes one empty rank, so cubes g and g + 2 never become adjacent. Ranks 0 and last + 1 are
/// empty too, so a neighbour rank r +- 1 of an occupied rank is never out of range.
struct RankedAxis {
    std::vector<double> grid;        ///< ascending; exact integers (doubles: any finite extent)
    std::vector<std::int32_t> rank;  ///< ascending, parallel to grid

    /// The rank of grid coordinate g: its own if occupied, else the empty rank where it falls.
    [[nodiscard]] std::int32_t rank_of(double g) const;
    /// The grid coordinate of occupied rank r.
    [[nodiscard]] double grid_of(std::int32_t r) const {
        const auto it = std::lower_bound(rank.begin(), rank.end(), r);
        return grid[static_cast<std::size_t>(it - rank.begin())];
    }
    /// Positions [first, last) in grid of the occupied coordinates within `reach` of rank r's
    /// grid coordinate; for an empty rank, within reach of any coordinate it stands for.
    [[nodiscard]] std::array<std::size_t, 2> within(std::int32_t r, int reach) const;
};

/// Ranked axes and the occupied (x, y) columns, ranked jointly. A cube's key is
/// (column rank << z_bits) | z rank: at most 31 + 31 bits, and key order is the (x, y, z) order
/// of the grid, as with packed grid keys.
struct RankedCubes {
    std::array<RankedAxis, 3> axes;
    std::vector<std::uint64_t> columns;  ///< (x rank << 32) | y rank, ascending
    int column_bits = 1;
    int z_bits = 1;

    /// Ranks the grid coordinates of the points (`grid[a][i]` on axis a of point i) and writes
    /// each point's key. Throws Error(kCloudTooLarge) if an axis has 2^30 distinct coordinates.
    RankedCubes(const std::array<std::span<const double>, 3>& grid, std::span<std::uint64_t> keys);

    [[nodiscard]] static std::uint64_t column(std::int32_t x, std::int32_t y) {
        return (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y);
    }
    [[nodiscard]] std::uint64_t key(std::size_t column_rank, std::int32_t z) const {
        return (std::uint64_t{column_rank} << z_bits) | std::uint32_t(z);
    }
    /// The (x, y, z) ranks of a cube key.
    [[nodiscard]] Eigen::Vector3i ranks(std::uint64_t key) const {
        const std::uint64_t c = columns[key >> z_bits];
        return {int(c >> 32), int(c & 0xffffffffu), int(key & ((std::uint64_t{1} << z_bits) - 1))};
    }
    /// The first column position >= p whose column is not below `col`, given that every
    /// position before p is (exponential then binary search: nearby columns cost a few steps).
    [[nodiscard]] std::size_t gallop_column(std::size_t p, std::uint64_t col) const;
};

}  // namespace surfgrow::detail
