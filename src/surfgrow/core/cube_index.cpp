#include "surfgrow/core/cube_index.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "surfgrow/core/detail/key_sort.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

using detail::BulkVector;
using detail::radix_sort_pairs;
using detail::reserve_bulk;

namespace {

// One part in 2^20: far below any physical meaning, far above float rounding (2^-24).
constexpr double kCubeInflation = 1.0 + 1.0 / (1 << 20);

bool included(std::span<const std::uint8_t> include, std::size_t i) {
    return include.empty() || include[i] != 0;
}

}  // namespace

CubeIndex::CubeIndex(std::span<const Vec3f> points, double cube_size,
                     std::span<const std::uint8_t> include, int threads) {
    if (!(cube_size > 0) || !std::isfinite(cube_size))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"cube size must be a positive length, got ", num(cube_size)}));
    if (!include.empty() && include.size() != points.size())
        throw Error(ErrorCode::kInternal, "cube index: include mask size differs from point count");
    if (points.size() >= (std::size_t{1} << 31))
        throw Error(ErrorCode::kCloudTooLarge, "more than 2^31 points; split the cloud");
    threads = std::max(1, threads);
    cube_size_ = cube_size * kCubeInflation;
    inv_cube_ = 1.0 / cube_size_;

    // Bounds of the indexed points, per chunk in parallel (min/max: same result in any order).
    const std::size_t n_in = points.size();
    const int team = n_in < (1u << 16) ? 1 : threads;
    const auto chunks = static_cast<std::size_t>(team);
    std::vector<std::size_t> chunk_count(chunks + 1, 0);
    std::vector<Vec3f> chunk_lo(chunks, Vec3f::Constant(std::numeric_limits<float>::max()));
    std::vector<Vec3f> chunk_hi(chunks, Vec3f::Constant(std::numeric_limits<float>::lowest()));
#pragma omp parallel for num_threads(team) schedule(static, 1)
    for (std::size_t c = 0; c < chunks; ++c) {
        Vec3f lo = chunk_lo[c], hi = chunk_hi[c];
        std::size_t k = 0;
        for (std::size_t i = n_in * c / chunks; i < n_in * (c + 1) / chunks; ++i) {
            if (!included(include, i) || !is_finite(points[i])) continue;
            lo = lo.cwiseMin(points[i]);
            hi = hi.cwiseMax(points[i]);
            ++k;
        }
        chunk_lo[c] = lo;
        chunk_hi[c] = hi;
        chunk_count[c + 1] = k;
    }
    Aabb box;
    for (std::size_t c = 0; c < chunks; ++c) {
        if (chunk_count[c + 1] == 0) continue;
        box.add(chunk_lo[c].cast<double>());
        box.add(chunk_hi[c].cast<double>());
    }
    for (std::size_t c = 0; c < chunks; ++c) chunk_count[c + 1] += chunk_count[c];  // prefix sums
    const std::size_t count = chunk_count[chunks];
    bounds_ = box;
    if (count == 0) {
        x_.assign(kPadding, 0.f);
        y_.assign(kPadding, 0.f);
        z_.assign(kPadding, 0.f);
        cube_start_.assign(1, 0);
        return;
    }
    // Half a cube plus one empty cube below the data: every occupied coordinate is >= 1, so every
    // neighbour coordinate is >= 0, whatever the float rounding of the local coordinates.
    origin_ = box.min - Vec3d::Constant(1.5 * cube_size_);
    const Vec3d span = (box.max - origin_) * inv_cube_;
    bool packed = true;
    for (int a = 0; a < 3 && packed; ++a) {
        // Highest coordinate is floor(span)+1 for the neighbour above; add 1 more for safety.
        const double top = std::floor(span[a]) + 2;
        packed = top < 2147483647.0;
        if (packed)
            bits_[a] =
                std::max(1, static_cast<int>(std::bit_width(static_cast<std::uint64_t>(top))));
    }
    BulkVector<std::uint64_t> keys(count);
    BulkVector<std::uint32_t> index(count);
    if (!packed || bits_.sum() > 63) {
        rank_keys(points, include, keys, index);
    } else {
        shift_y_ = bits_.z();
        shift_x_ = bits_.z() + bits_.y();
        // Keys and input indices of the included finite points, in input order, each chunk
        // written at its prefix offset. Keys come from the float local coordinates the queries
        // use, so a point's cube and its distances agree exactly (truncation equals floor: local
        // coordinates are > 0).
#pragma omp parallel for num_threads(team) schedule(static, 1)
        for (std::size_t c = 0; c < chunks; ++c) {
            std::size_t k = chunk_count[c];
            for (std::size_t i = n_in * c / chunks; i < n_in * (c + 1) / chunks; ++i) {
                if (!included(include, i) || !is_finite(points[i])) continue;
                const Vec3f l = local_of(points[i]);
                const Eigen::Vector3i coords(
                    static_cast<int>(static_cast<double>(l.x()) * inv_cube_),
                    static_cast<int>(static_cast<double>(l.y()) * inv_cube_),
                    static_cast<int>(static_cast<double>(l.z()) * inv_cube_));
                keys[k] = encode(coords);
                index[k] = static_cast<std::uint32_t>(i);
                ++k;
            }
        }
    }
    radix_sort_pairs(keys, index, bits_.sum(), threads);

    // Gather coordinates in sorted order; find cube boundaries.
    const std::size_t n = count;
    x_.resize(n + kPadding);
    y_.resize(n + kPadding);
    z_.resize(n + kPadding);
    std::fill(x_.begin() + static_cast<std::ptrdiff_t>(n), x_.end(), 0.f);  // readable padding
    std::fill(y_.begin() + static_cast<std::ptrdiff_t>(n), y_.end(), 0.f);
    std::fill(z_.begin() + static_cast<std::ptrdiff_t>(n), z_.end(), 0.f);
#pragma omp parallel for num_threads(threads) schedule(static) if (n > (1u << 16))
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3f local = local_of(points[index[i]]);
        x_[i] = local.x();
        y_[i] = local.y();
        z_[i] = local.z();
    }
    // Cube boundaries: each chunk counts the cubes starting in it, then writes them at its offset.
    const int sweep_team = n < (1u << 16) ? 1 : threads;
    const auto sweep_chunks = static_cast<std::size_t>(sweep_team);
    std::vector<std::size_t> cubes_before(sweep_chunks + 1, 0);
    auto starts_cube = [&](std::size_t i) { return i == 0 || keys[i] != keys[i - 1]; };
#pragma omp parallel for num_threads(sweep_team) schedule(static, 1)
    for (std::size_t c = 0; c < sweep_chunks; ++c) {
        std::size_t k = 0;
        for (std::size_t i = n * c / sweep_chunks; i < n * (c + 1) / sweep_chunks; ++i)
            k += starts_cube(i) ? 1 : 0;
        cubes_before[c + 1] = k;
    }
    for (std::size_t c = 0; c < sweep_chunks; ++c) cubes_before[c + 1] += cubes_before[c];
    const std::size_t cubes = cubes_before[sweep_chunks];
    cube_keys_.clear();
    cube_start_.clear();
    reserve_bulk(cube_keys_, cubes);
    reserve_bulk(cube_start_, cubes + 1);
    cube_keys_.resize(cubes);
    cube_start_.resize(cubes + 1);
#pragma omp parallel for num_threads(sweep_team) schedule(static, 1)
    for (std::size_t c = 0; c < sweep_chunks; ++c) {
        std::size_t k = cubes_before[c];
        for (std::size_t i = n * c / sweep_chunks; i < n * (c + 1) / sweep_chunks; ++i) {
            if (!starts_cube(i)) continue;
            cube_keys_[k] = keys[i];
            cube_start_[k] = static_cast<std::uint32_t>(i);
            ++k;
        }
    }
    cube_start_[cubes] = static_cast<std::uint32_t>(n);
    original_ = std::move(index);
}

std::uint32_t CubeIndex::cube_of(std::uint32_t i, std::uint32_t first, std::uint32_t last) const {
    const auto it = std::upper_bound(cube_start_.begin() + first, cube_start_.begin() + last, i);
    return static_cast<std::uint32_t>(it - cube_start_.begin() - 1);
}

void CubeIndex::rank_keys(std::span<const Vec3f> points, std::span<const std::uint8_t> include,
                          BulkVector<std::uint64_t>& keys, BulkVector<std::uint32_t>& index) {
    // Local coordinates must stay finite floats for the queries' arithmetic.
    const Vec3d extent = bounds_.max - origin_;
    if (!(extent.maxCoeff() < double(std::numeric_limits<float>::max())))
        throw Error(
            ErrorCode::kCloudTooLarge,
            cat({"the cloud's extent (", num(bounds_.size().x()), " x ", num(bounds_.size().y()),
                 " x ", num(bounds_.size().z()),
                 ") is beyond float range; crop the workspace or look for outlier points"}));
    std::array<std::vector<double>, 3> grid;
    for (auto& g : grid) g.resize(keys.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!included(include, i) || !is_finite(points[i])) continue;
        const Vec3f l = local_of(points[i]);
        for (int a = 0; a < 3; ++a)
            grid[static_cast<std::size_t>(a)][k] =
                std::floor(static_cast<double>(l[a]) * inv_cube_);
        index[k] = static_cast<std::uint32_t>(i);
        ++k;
    }
    ranked_ = std::make_shared<const detail::RankedCubes>(
        std::array<std::span<const double>, 3>{grid[0], grid[1], grid[2]},
        std::span<std::uint64_t>(keys.data(), keys.size()));
    bits_ = {ranked_->column_bits, 0, ranked_->z_bits};
}

Vec3d CubeIndex::grid_coords(std::size_t c) const {
    const Eigen::Vector3i r = cube_coords(c);
    if (!ranked_) return r.cast<double>();
    return {ranked_->axes[0].grid_of(r.x()), ranked_->axes[1].grid_of(r.y()),
            ranked_->axes[2].grid_of(r.z())};
}

Eigen::Vector3i CubeIndex::coords_of(const Vec3f& local) const {
    Eigen::Vector3i c;
    if (ranked_) {
        for (int a = 0; a < 3; ++a)
            c[a] = ranked_->axes[static_cast<std::size_t>(a)].rank_of(
                std::floor(static_cast<double>(local[a]) * inv_cube_));
        return c;
    }
    for (int a = 0; a < 3; ++a) {
        const double v = std::floor(static_cast<double>(local[a]) * inv_cube_);
        c[a] = static_cast<int>(std::clamp(v, -1073741824.0, 1073741824.0));
    }
    return c;
}

void CubeIndex::column_ranges(const Eigen::Vector3i& coords, int reach,
                              std::vector<Range>& out) const {
    for_each_column_run(coords, reach, [&](const Range& r) { out.push_back(r); });
}

void CubeIndex::column_cube_ranges(const Eigen::Vector3i& coords, int reach,
                                   std::vector<Range>& out) const {
    for_each_column_cubes(coords, reach, [&](const Range& r) { out.push_back(r); });
}

std::size_t CubeIndex::gallop_to(std::size_t p, std::uint64_t key, bool inclusive) const {
    // Exponential search from p, then binary search: O(log distance), so runs of nearby columns
    // cost a few steps each instead of a search over all cubes.
    auto before = [&](std::uint64_t k) { return inclusive ? k <= key : k < key; };
    const std::size_t n = cube_keys_.size();
    std::size_t lo = p, hi = p, step = 1;
    while (hi < n && before(cube_keys_[hi])) {
        lo = hi + 1;
        hi = lo + step - 1;
        step *= 2;
    }
    hi = std::min(hi, n);
    return static_cast<std::size_t>(
        std::partition_point(cube_keys_.begin() + static_cast<std::ptrdiff_t>(lo),
                             cube_keys_.begin() + static_cast<std::ptrdiff_t>(hi), before) -
        cube_keys_.begin());
}

void CubeIndex::neighbour_table(std::size_t cube_begin, std::size_t cube_end,
                                std::vector<Range>& out) const {
    const std::size_t m = cube_end - cube_begin;
    out.assign(9 * m, Range{});
    if (m == 0) return;
    if (ranked_) {
        ranked_neighbour_table(cube_begin, cube_end, out);
        return;
    }
    const std::size_t nc = cube_keys_.size();
    int k = 0;
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy, ++k) {
            // key(x+dx, y+dy, z-1) = key + delta - 1: no borrow or carry crosses a field because
            // every occupied coordinate is >= 1 and <= 2^bits - 2.
            const auto delta = static_cast<std::int64_t>((std::int64_t{dx} << shift_x_) +
                                                         (std::int64_t{dy} << shift_y_));
            auto lo_key = [&](std::size_t c) {
                return std::uint64_t(std::int64_t(cube_keys_[c]) + delta - 1);
            };
            auto hi_key = [&](std::size_t c) {
                return std::uint64_t(std::int64_t(cube_keys_[c]) + delta + 1);
            };
            std::size_t a = static_cast<std::size_t>(
                std::lower_bound(cube_keys_.begin(), cube_keys_.end(), lo_key(cube_begin)) -
                cube_keys_.begin());
            std::size_t b = a;
            for (std::size_t c = cube_begin; c < cube_end; ++c) {
                const std::uint64_t lo = lo_key(c), hi = hi_key(c);
                while (a < nc && cube_keys_[a] < lo) ++a;
                if (b < a) b = a;
                while (b < nc && cube_keys_[b] <= hi) ++b;
                out[9 * (c - cube_begin) + static_cast<std::size_t>(k)] = {cube_start_[a],
                                                                           cube_start_[b]};
            }
        }
    }
}

void CubeIndex::ranked_neighbour_table(std::size_t cube_begin, std::size_t cube_end,
                                       std::vector<Range>& out) const {
    // Ranks keep adjacency, so the neighbour columns are (x +- 1, y +- 1) in ranks; for each
    // (dx, dy) they and the keys they start at rise with the cube, as in the packed sweep.
    const detail::RankedCubes& rc = *ranked_;
    int k = 0;
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy, ++k) {
            std::size_t column = 0, a = 0, b = 0;
            for (std::size_t c = cube_begin; c < cube_end; ++c) {
                const Eigen::Vector3i r = rc.ranks(cube_keys_[c]);  // ranks >= 1: r - 1 >= 0
                const std::uint64_t want = rc.column(r.x() + dx, r.y() + dy);
                column = rc.gallop_column(column, want);
                if (column == rc.columns.size() || rc.columns[column] != want) continue;
                a = gallop_to(a, rc.key(column, r.z() - 1), false);
                b = gallop_to(std::max(a, b), rc.key(column, r.z() + 1), true);
                out[9 * (c - cube_begin) + static_cast<std::size_t>(k)] = {cube_start_[a],
                                                                           cube_start_[b]};
            }
        }
    }
}

}  // namespace surfgrow
