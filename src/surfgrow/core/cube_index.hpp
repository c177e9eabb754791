// The cube index of paper section 4.1: space cut into cubes of side mu, points filed by cube.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "surfgrow/core/detail/bulk_allocator.hpp"
#include "surfgrow/core/detail/ranked_cubes.hpp"
#include "surfgrow/core/detail/simd_kernels.hpp"
#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// Points sorted by cube, in structure-of-arrays form, with the cubes' keys and point ranges.
///
/// Built in O(N) by a radix sort of packed cube keys; memory is O(N) whatever the cloud's extent
/// (only occupied cubes exist). Cube coordinates are packed into one 64-bit key with x in the
/// high bits and z in the low bits, so the 3 cubes of a z-column are adjacent in key order and
/// the 27 cubes around a cube are 9 contiguous runs of the sorted points.
///
/// A cloud whose grid coordinates would need more than 63 key bits (or 2^31 cubes on an axis) is
/// indexed by ranks instead (ranked(), detail::RankedCubes): each axis's occupied coordinates are
/// ranked with gaps kept, so adjacency is exact, and the key is (x-y column rank, z rank). Key
/// order and every run are then the same as the grid's; only cube coordinates are ranks.
///
/// Coordinates are stored as float relative to origin(), the low corner of the indexed points'
/// bounding box less one and a half cubes. The cube side is the requested size enlarged by one part
/// in 2^20, so that no float rounding can put two points within the requested size more than one
/// cube apart: a radius query never misses a point.
class CubeIndex {
  public:
    /// A run [begin, end) of sorted point positions (the kernels' own type: they read them).
    using Range = detail::IndexRun;
    /// Readable floats past size() in each coordinate array, so SIMD loops may overrun a range.
    static constexpr std::size_t kPadding = 64;

    CubeIndex() = default;

    /// Indexes every finite point `points[i]` for which `include` is empty or include[i] != 0.
    /// Any finite extent is indexed. Throws Error(kInvalidParameter) for a bad cube size,
    /// Error(kCloudTooLarge) for 2^31 points or more, an extent beyond float range, or 2^30
    /// distinct cube positions on one axis.
    CubeIndex(std::span<const Vec3f> points, double cube_size,
              std::span<const std::uint8_t> include = {}, int threads = 1);

    [[nodiscard]] double cube_size() const { return cube_size_; }
    [[nodiscard]] std::size_t size() const { return original_.size(); }
    [[nodiscard]] std::size_t cube_count() const { return cube_keys_.size(); }
    [[nodiscard]] const Vec3d& origin() const { return origin_; }
    /// Bounding box of the indexed points (world coordinates); empty if none.
    [[nodiscard]] const Aabb& bounds() const { return bounds_; }
    /// A world position in the index's local float frame.
    [[nodiscard]] Vec3f to_local(const Vec3d& world) const {
        return (world - origin_).cast<float>();
    }

    /// Sorted local coordinates (world minus origin()); each array has kPadding readable extras.
    [[nodiscard]] const float* xs() const { return x_.data(); }
    [[nodiscard]] const float* ys() const { return y_.data(); }
    [[nodiscard]] const float* zs() const { return z_.data(); }
    [[nodiscard]] Vec3f local_point(std::uint32_t i) const { return {x_[i], y_[i], z_[i]}; }
    [[nodiscard]] Vec3d world_point(std::uint32_t i) const {
        return origin_ + local_point(i).cast<double>();
    }
    /// Input index of the point at sorted position i.
    [[nodiscard]] std::span<const std::uint32_t> original_indices() const { return original_; }

    /// Cube c's key and its points [cube_begin(c), cube_end(c)).
    [[nodiscard]] std::uint64_t cube_key(std::size_t c) const { return cube_keys_[c]; }
    [[nodiscard]] std::uint32_t cube_begin(std::size_t c) const { return cube_start_[c]; }
    [[nodiscard]] std::uint32_t cube_end(std::size_t c) const { return cube_start_[c + 1]; }
    /// Whether cube coordinates are ranks (a cloud too wide for packed grid coordinates).
    [[nodiscard]] bool ranked() const { return ranked_ != nullptr; }
    /// Cube c's coordinates in the index's frame, for coords_of() and for_each_column_run(): its
    /// grid coordinates, or its ranks if ranked() (adjacent cubes keep adjacent coordinates).
    [[nodiscard]] Eigen::Vector3i cube_coords(std::size_t c) const {
        return ranked_ ? ranked_->ranks(cube_keys_[c]) : decode(cube_keys_[c]);
    }
    /// Cube c's grid coordinates: it covers origin() + [g, g + 1) * cube_size() on each axis.
    /// Exact integers (double: any extent); equal to cube_coords() unless ranked().
    [[nodiscard]] Vec3d grid_coords(std::size_t c) const;
    /// The cube holding sorted point i (binary search).
    [[nodiscard]] std::uint32_t cube_of(std::uint32_t i) const {
        return cube_of(i, 0, static_cast<std::uint32_t>(cube_count()));
    }
    /// The same, searching only the cubes [first, last), which must hold point i.
    [[nodiscard]] std::uint32_t cube_of(std::uint32_t i, std::uint32_t first,
                                        std::uint32_t last) const;
    /// The cube coordinates a local position falls in (may be outside the occupied cubes; if
    /// ranked(), an empty rank stands for all the empty coordinates between two occupied ones).
    [[nodiscard]] Eigen::Vector3i coords_of(const Vec3f& local) const;

    /// Calls f(run) for the (2*reach+1)^2 z-column runs covering every cube within `reach` cubes
    /// (in x, y and z) of the cube at `coords`, in key order. Empty runs are skipped. One cursor
    /// sweeps forward through the cube keys (galloping search), as the columns' keys increase.
    template <class F>
    void for_each_column_run(const Eigen::Vector3i& coords, int reach, F&& f) const;

    /// Appends the runs of for_each_column_run() to `out`.
    void column_ranges(const Eigen::Vector3i& coords, int reach, std::vector<Range>& out) const;
    /// The same runs as cube numbers: [begin, end) of cube_begin()/cube_end(), not of points.
    void column_cube_ranges(const Eigen::Vector3i& coords, int reach,
                            std::vector<Range>& out) const;

    /// The 9 runs around each cube in [cube_begin, cube_end), in one linear sweep:
    /// out[9 * (c - cube_begin) + k]. Faster than column_ranges() when most cubes are visited.
    void neighbour_table(std::size_t cube_begin, std::size_t cube_end,
                         std::vector<Range>& out) const;

    /// Calls f(sorted_index) for every indexed point within `radius` (world units, any size) of
    /// the world position q, in sorted order.
    template <class F>
    void for_each_within(const Vec3d& q, double radius, F&& f) const;

    /// Number of key bits per axis (x, y, z), for tests and diagnostics; if ranked(), the column
    /// rank's bits, 0 and the z rank's bits.
    [[nodiscard]] Eigen::Vector3i key_bits() const { return bits_; }

  private:
    /// for_each_column_run()'s columns as cube numbers [begin, end).
    template <class F>
    void for_each_column_cubes(const Eigen::Vector3i& coords, int reach, F&& f) const;
    template <class F>
    void for_each_ranked_column_cubes(const Eigen::Vector3i& coords, int reach, F&& f) const;
    /// Keys and input indices of the `count` included finite points, by ranks (sets ranked_).
    void rank_keys(std::span<const Vec3f> points, std::span<const std::uint8_t> include,
                   detail::BulkVector<std::uint64_t>& keys,
                   detail::BulkVector<std::uint32_t>& index);
    void ranked_neighbour_table(std::size_t cube_begin, std::size_t cube_end,
                                std::vector<Range>& out) const;
    /// The first cube position >= p whose key is not below `key` (above, if `inclusive`), given
    /// that every position before p is.
    [[nodiscard]] std::size_t gallop_to(std::size_t p, std::uint64_t key, bool inclusive) const;
    [[nodiscard]] Vec3f local_of(const Vec3f& p) const {
        return (p.cast<double>() - origin_).cast<float>();
    }
    [[nodiscard]] std::uint64_t encode(const Eigen::Vector3i& c) const {
        return (std::uint64_t(std::uint32_t(c.x())) << shift_x_) |
               (std::uint64_t(std::uint32_t(c.y())) << shift_y_) |
               std::uint64_t(std::uint32_t(c.z()));
    }
    [[nodiscard]] Eigen::Vector3i decode(std::uint64_t key) const {
        const std::uint64_t my = (std::uint64_t{1} << bits_.y()) - 1;
        const std::uint64_t mz = (std::uint64_t{1} << bits_.z()) - 1;
        return {int(key >> shift_x_), int((key >> shift_y_) & my), int(key & mz)};
    }
    [[nodiscard]] bool in_key_space(const Eigen::Vector3i& c) const {
        return (c.array() >= 0).all() && c.x() < (std::int64_t{1} << bits_.x()) &&
               c.y() < (std::int64_t{1} << bits_.y()) && c.z() < (std::int64_t{1} << bits_.z());
    }

    double cube_size_ = 0.0;
    double inv_cube_ = 0.0;
    Vec3d origin_ = Vec3d::Zero();
    Aabb bounds_;
    Eigen::Vector3i bits_ = Eigen::Vector3i::Zero();
    int shift_x_ = 0;
    int shift_y_ = 0;
    detail::BulkVector<float> x_, y_, z_;
    detail::BulkVector<std::uint32_t> original_;
    std::vector<std::uint64_t> cube_keys_;
    std::vector<std::uint32_t> cube_start_;              // cube_count() + 1 entries
    std::shared_ptr<const detail::RankedCubes> ranked_;  // null: packed grid keys
};

template <class F>
void CubeIndex::for_each_within(const Vec3d& q, double radius, F&& f) const {
    if (size() == 0 || !(radius >= 0)) return;
    const Vec3f ql = (q - origin_).cast<float>();
    const auto r2 = static_cast<float>(radius * radius);
    auto scan = [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t i = begin; i < end; ++i) {
            const float dx = x_[i] - ql.x(), dy = y_[i] - ql.y(), dz = z_[i] - ql.z();
            if (dx * dx + dy * dy + dz * dz <= r2) f(i);
        }
    };
    const double reach = std::ceil(radius * inv_cube_);
    if ((2 * reach + 1) * (2 * reach + 1) > double(cube_count())) {
        scan(0, static_cast<std::uint32_t>(size()));  // cheaper than visiting the columns
        return;
    }
    for_each_column_run(coords_of(ql), static_cast<int>(reach),
                        [&](const Range& run) { scan(run.begin, run.end); });
}

template <class F>
void CubeIndex::for_each_column_run(const Eigen::Vector3i& coords, int reach, F&& f) const {
    for_each_column_cubes(coords, reach, [&](const Range& cubes) {
        f(Range{cube_start_[cubes.begin], cube_start_[cubes.end]});
    });
}

template <class F>
void CubeIndex::for_each_column_cubes(const Eigen::Vector3i& coords, int reach, F&& f) const {
    if (reach < 0 || cube_keys_.empty()) return;
    if (ranked_) {
        for_each_ranked_column_cubes(coords, reach, f);
        return;
    }
    const auto zmax = static_cast<int>((std::int64_t{1} << bits_.z()) - 1);
    const int zlo = std::max(0, coords.z() - reach);
    const int zhi = std::min(zmax, coords.z() + reach);
    if (zlo > zhi) return;
    std::size_t cursor = 0;
    for (int dx = -reach; dx <= reach; ++dx) {
        for (int dy = -reach; dy <= reach; ++dy) {
            const int x = coords.x() + dx, y = coords.y() + dy;
            if (!in_key_space({x, y, zlo})) continue;
            const std::size_t first = gallop_to(cursor, encode({x, y, zlo}), false);
            const std::size_t last = gallop_to(first, encode({x, y, zhi}), true);
            cursor = last;
            if (first < last)
                f(Range{static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(last)});
        }
    }
}

template <class F>
void CubeIndex::for_each_ranked_column_cubes(const Eigen::Vector3i& coords, int reach,
                                             F&& f) const {
    // The occupied grid coordinates within reach on each axis, then their columns in key order:
    // the same runs as the grid's layout gives.
    const detail::RankedCubes& rc = *ranked_;
    const auto [x0, x1] = rc.axes[0].within(coords.x(), reach);
    const auto [y0, y1] = rc.axes[1].within(coords.y(), reach);
    const auto [z0, z1] = rc.axes[2].within(coords.z(), reach);
    if (x0 == x1 || y0 == y1 || z0 == z1) return;
    const std::int32_t zlo = rc.axes[2].rank[z0], zhi = rc.axes[2].rank[z1 - 1];
    std::size_t column = 0, cursor = 0;
    for (std::size_t i = x0; i < x1; ++i) {
        for (std::size_t j = y0; j < y1; ++j) {
            const std::uint64_t want = rc.column(rc.axes[0].rank[i], rc.axes[1].rank[j]);
            column = rc.gallop_column(column, want);
            if (column == rc.columns.size()) return;
            if (rc.columns[column] != want) continue;
            const std::size_t first = gallop_to(cursor, rc.key(column, zlo), false);
            const std::size_t last = gallop_to(first, rc.key(column, zhi), true);
            cursor = last;
            if (first < last)
                f(Range{static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(last)});
        }
    }
}

}  // namespace surfgrow
