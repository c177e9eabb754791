// Which patches touch: the patch graph that bound planes grow their regions on, and the
// key and search helpers it shares with gap bridging.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/surface.hpp"
#include "surfgrow/planes/patch_members.hpp"

namespace surfgrow {

/// An unordered pair of ids as one sortable key: smaller id in the high half.
[[nodiscard]] inline std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

/// The ids pair_key packed: (smaller, larger).
[[nodiscard]] inline std::pair<std::uint32_t, std::uint32_t> pair_of_key(std::uint64_t key) {
    return {static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key & 0xffffffffu)};
}

/// The keys of every part, sorted and unique: the same whatever the split into parts.
[[nodiscard]] std::vector<std::uint64_t> merged_unique(
    std::initializer_list<const std::vector<std::vector<std::uint64_t>>*> sources);

/// How far rounding to float can move the distance between two positions indexed by `index`
/// (world coordinates in float, then made local): the margin a float search needs so that it
/// never drops a pair the exact test in double would keep.
[[nodiscard]] inline double float_rounding_slack(const CubeIndex& index) {
    const Aabb& b = index.bounds();
    if (b.empty()) return 0;
    const double largest = std::max(b.min.cwiseAbs().maxCoeff(), b.max.cwiseAbs().maxCoeff());
    return 4 * static_cast<double>(std::numeric_limits<float>::epsilon()) *
           (largest + b.size().maxCoeff());
}

/// An index built for searches of a typical reach takes cubes this much larger than that reach:
/// search_ring()'s margins push such a search just past one cube, which would double the columns'
/// side (25 instead of 9).
constexpr double kSearchSideMargin = 1.01;

/// How many cubes on each side of its own a search of `reach` (world units) visits. The margin
/// makes a reach of exactly k cubes search k + 1: the cube side is enlarged by 2^-20 against
/// float rounding, which a ratio rounded down could undo.
[[nodiscard]] inline double search_ring(const CubeIndex& index, double reach) {
    return std::max(1.0, std::ceil(reach / index.cube_size() * (1 + 1e-6)));
}

/// Whether the columns of a search `ring` cubes wide would outnumber the index's cubes (a search
/// as large as the cloud): then it reads every point in one run instead.
[[nodiscard]] inline bool search_spans_index(const CubeIndex& index, double ring) {
    return (2 * ring + 1) * (2 * ring + 1) > static_cast<double>(index.cube_count());
}

/// Calls f(run) for runs of `index` holding every point within `reach` (world units) of the local
/// position `h`: the column runs of the cubes around it, or every point in one run
/// (search_spans_index).
template <class F>
void for_each_run_near(const CubeIndex& index, const Vec3f& h, double reach, F&& f) {
    const double ring = search_ring(index, reach);
    if (search_spans_index(index, ring)) {
        f(CubeIndex::Range{0, static_cast<std::uint32_t>(index.size())});
        return;
    }
    index.for_each_column_run(index.coords_of(h), static_cast<int>(ring), f);
}

/// Calls f(j) for each home j of `index` (an index over home points) that lies within `reach`
/// of `home` and that `next` admits: `next(j)` returns j to test it, or the
/// first later index worth a test (skipping, say, a run of homes of the patch's own region)
/// before any distance is computed.
template <class Next, class F>
void for_each_home_near(const CubeIndex& index, const Vec3d& home, double reach, Next&& next,
                        F&& f) {
    const Vec3f h = index.to_local(home);
    reach += float_rounding_slack(index);
    const auto r2 = static_cast<float>(reach * reach);
    const float* X = index.xs();
    const float* Y = index.ys();
    const float* Z = index.zs();
    for_each_run_near(index, h, reach, [&](const CubeIndex::Range& run) {
        for (std::uint32_t j = run.begin; j < run.end;) {
            const std::uint32_t k = next(j);
            if (k != j) {
                j = std::max(k, j + 1);
                continue;
            }
            const float dx = X[j] - h.x(), dy = Y[j] - h.y(), dz = Z[j] - h.z();
            if (dx * dx + dy * dy + dz * dz <= r2) f(j);
            ++j;
        }
    });
}

/// Adjacency of patches: member points within `reach` of each other, or home points within the
/// sum of the radii, among the surfaces with members. Sorted, unique pairs (a < b); the same for
/// any thread count.
[[nodiscard]] std::vector<std::pair<std::uint32_t, std::uint32_t>> adjacent_patch_pairs(
    const PatchMembers& members, std::span<const Surface> surfaces, double reach, int threads);

/// The same pairs as keys (pair_key), sorted, from each patch's member box (`boxes`, empty where
/// a patch has none), seeking only the pairs of which a patch is marked in `changed`: `known`
/// holds the pairs found before among the unmarked ones, whose members did not change since
/// (adjacency only grows with members, so `known` stays true). With every patch marked and
/// nothing known, a search of all pairs.
[[nodiscard]] std::vector<std::uint64_t> adjacent_patch_keys(const PatchMembers& members,
                                                             std::span<const Surface> surfaces,
                                                             const std::vector<Aabb>& boxes,
                                                             std::span<const std::uint8_t> changed,
                                                             std::span<const std::uint64_t> known,
                                                             double reach, int threads);

}  // namespace surfgrow
