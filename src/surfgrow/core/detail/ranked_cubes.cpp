#include "surfgrow/core/detail/ranked_cubes.hpp"

#include <bit>
#include <limits>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::detail {

namespace {

// The last rank plus one must fit an int, and z ranks 31 key bits.
constexpr std::int64_t kMaxRank = (std::int64_t{1} << 31) - 2;

RankedAxis rank_axis(std::span<const double> grid, int axis) {
    RankedAxis a;
    a.grid.assign(grid.begin(), grid.end());
    std::sort(a.grid.begin(), a.grid.end());
    a.grid.erase(std::unique(a.grid.begin(), a.grid.end()), a.grid.end());
    a.rank.reserve(a.grid.size());
    std::int64_t r = 1;
    for (std::size_t i = 0; i < a.grid.size(); ++i) {
        // Exact for adjacent integers below 2^53; above, distinct doubles are >= 2 apart anyway.
        if (i > 0) r += a.grid[i] == a.grid[i - 1] + 1 ? 1 : 2;
        if (r >= kMaxRank)
            throw Error(ErrorCode::kCloudTooLarge,
                        cat({"the cloud has more than 2^30 distinct cube positions along ",
                             std::string(1, "xyz"[axis]), "; use a larger mu"}));
        a.rank.push_back(static_cast<std::int32_t>(r));
    }
    return a;
}

}  // namespace

std::int32_t RankedAxis::rank_of(double g) const {
    const auto j =
        static_cast<std::size_t>(std::lower_bound(grid.begin(), grid.end(), g) - grid.begin());
    if (j < grid.size() && grid[j] == g) return rank[j];
    return j == 0 ? rank.front() - 1 : rank[j - 1] + 1;
}

std::array<std::size_t, 2> RankedAxis::within(std::int32_t r, int reach) const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const auto j =
        static_cast<std::size_t>(std::lower_bound(rank.begin(), rank.end(), r) - rank.begin());
    double lo, hi;
    if (j < rank.size() && rank[j] == r) {
        lo = grid[j] - reach;
        hi = grid[j] + reach;
    } else {  // an empty rank stands for every coordinate between its occupied neighbours
        lo = (j > 0 ? grid[j - 1] + 1 : -kInf) - reach;
        hi = (j < grid.size() ? grid[j] - 1 : kInf) + reach;
    }
    // Rounding to nearest is monotone, so a rounded bound never excludes a coordinate in range.
    const auto first = std::lower_bound(grid.begin(), grid.end(), lo);
    const auto last = std::upper_bound(first, grid.end(), hi);
    return {static_cast<std::size_t>(first - grid.begin()),
            static_cast<std::size_t>(last - grid.begin())};
}

RankedCubes::RankedCubes(const std::array<std::span<const double>, 3>& grid,
                         std::span<std::uint64_t> keys) {
    const std::size_t n = keys.size();
    for (int a = 0; a < 3; ++a) axes[static_cast<std::size_t>(a)] = rank_axis(grid[a], a);
    auto rank_of_point = [&](int a, std::size_t i) {
        const RankedAxis& axis = axes[static_cast<std::size_t>(a)];
        const auto it = std::lower_bound(axis.grid.begin(), axis.grid.end(), grid[a][i]);
        return axis.rank[static_cast<std::size_t>(it - axis.grid.begin())];
    };
    // Each point's column first (in keys), then its rank among the occupied columns.
    for (std::size_t i = 0; i < n; ++i) keys[i] = column(rank_of_point(0, i), rank_of_point(1, i));
    columns.assign(keys.begin(), keys.end());
    std::sort(columns.begin(), columns.end());
    columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
    column_bits = std::max(1, static_cast<int>(std::bit_width(columns.size() - 1)));
    z_bits = static_cast<int>(std::bit_width(
        static_cast<std::uint32_t>(axes[2].rank.empty() ? 1 : axes[2].rank.back() + 1)));
    for (std::size_t i = 0; i < n; ++i) {
        const auto col =
            std::lower_bound(columns.begin(), columns.end(), keys[i]) - columns.begin();
        keys[i] = key(static_cast<std::size_t>(col), rank_of_point(2, i));
    }
}

std::size_t RankedCubes::gallop_column(std::size_t p, std::uint64_t col) const {
    const std::size_t n = columns.size();
    std::size_t lo = p, hi = p, step = 1;
    while (hi < n && columns[hi] < col) {
        lo = hi + 1;
        hi = lo + step - 1;
        step *= 2;
    }
    hi = std::min(hi, n);
    return static_cast<std::size_t>(
        std::lower_bound(columns.begin() + static_cast<std::ptrdiff_t>(lo),
                         columns.begin() + static_cast<std::ptrdiff_t>(hi), col) -
        columns.begin());
}

}  // namespace surfgrow::detail
