#include "surfgrow/core/detail/edge_pass.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <utility>

#include "surfgrow/core/detail/cube_surfaces.hpp"
#include "surfgrow/core/detail/parallel_errors.hpp"

namespace surfgrow::detail {

namespace {

// Surfaces whose normals differ by more than this (cos 30 degrees) lie across an edge.
constexpr double kEdgeCos = 0.8660254037844387;
// A surface's layer in a scan is its plane shifted to the mean of that scan's members where it
// has at least this many; with fewer, the plane itself.
constexpr std::uint32_t kMinLayerMembers = 5;
// The per-scan table (surfaces x scans) is built only up to this many entries per point.
constexpr std::size_t kMaxLayerEntriesPerPoint = 4;

/// Whether two surfaces lie across an edge from each other.
bool across(const Surface& a, const Surface& b) {
    return std::abs(a.normal.dot(b.normal)) < kEdgeCos;
}

/// Per surface and scan, how far that scan's members lie from the surface's plane on average.
struct LayerShifts {
    std::size_t scans = 0;
    std::vector<double> shift;  // [surface * scans + scan]

    [[nodiscard]] double of(std::size_t surface, std::size_t scan) const {
        return shift[surface * scans + scan];
    }
};

/// A point's signed distance to a surface's plane (world frame).
double signed_distance(const Surface& s, const Vec3d& p) {
    return s.normal.dot(p - s.centroid);
}

/// The distances on all threads; their sums in index order on one: the same bits for any thread
/// count.
LayerShifts layer_shifts(const GrowContext& ctx, const std::vector<Surface>& surfaces,
                         std::span<const std::int32_t> labels, int threads) {
    LayerShifts ls;
    ls.scans = ctx.sight.origins.size();
    const CubeIndex& index = ctx.index;
    const auto n = static_cast<std::uint32_t>(labels.size());
    std::vector<float> distance(n);
    std::vector<std::uint32_t> scan(n);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::int32_t l = labels[i];
        scan[i] = ctx.sight.scan_of(i);
        if (l >= 0)
            distance[i] = static_cast<float>(
                signed_distance(surfaces[static_cast<std::size_t>(l)], index.world_point(i)));
    }
    const std::size_t entries = surfaces.size() * ls.scans;
    std::vector<double> sum(entries, 0.0);
    std::vector<std::uint32_t> count(entries, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
        if (labels[i] < 0 || scan[i] >= ls.scans) continue;
        const std::size_t k = static_cast<std::size_t>(labels[i]) * ls.scans + scan[i];
        sum[k] += static_cast<double>(distance[i]);
        ++count[k];
    }
    ls.shift.assign(entries, 0.0);
    for (std::size_t k = 0; k < entries; ++k)
        if (count[k] >= kMinLayerMembers) ls.shift[k] = sum[k] / count[k];
    return ls;
}

/// A thread's buffers (a cache line of its own, as Scratch).
struct alignas(64) EdgeScratch {
    std::vector<Range> runs;           // of cubes
    std::vector<std::uint32_t> cubes;  // the 27 around the current one
    std::vector<std::int32_t> around;  // their surfaces
    std::vector<std::uint32_t> seen;   // per surface: last listing's stamp
    std::uint32_t stamp = 0;
    std::vector<std::pair<double, std::int32_t>> fitting;
};

/// The cubes within one of cube c (itself included), into s.cubes.
void cubes_around(const CubeIndex& index, std::uint32_t c, EdgeScratch& s) {
    s.runs.clear();
    index.column_cube_ranges(index.cube_coords(c), 1, s.runs);
    s.cubes.clear();
    for (const Range& run : s.runs)
        for (std::uint32_t k = run.begin; k < run.end; ++k) s.cubes.push_back(k);
}

/// Marks, in `near_edge`, the cubes within one of a cube whose own points were registered to
/// surfaces across an edge: the only cubes where a surface across the edge is within reach.
void mark_edges(const CubeIndex& index, const Slab& slab, const std::vector<Surface>& surfaces,
                const CubeSurfaces& near, EdgeScratch& s, std::vector<std::uint8_t>& near_edge) {
    for (std::uint32_t c = slab.cube_begin; c < slab.cube_end; ++c) {
        const auto list = near.of(c);
        bool edge = false;
        for (std::size_t a = 0; a < list.size() && !edge; ++a)
            for (std::size_t b = a + 1; b < list.size() && !edge; ++b)
                edge = across(surfaces[static_cast<std::size_t>(list[a])],
                              surfaces[static_cast<std::size_t>(list[b])]);
        if (!edge) continue;
        cubes_around(index, c, s);
        for (const std::uint32_t k : s.cubes)
            std::atomic_ref<std::uint8_t>(near_edge[k]).store(1, std::memory_order_relaxed);
    }
}

/// The moves of the points of one slab's cubes near an edge: read from the labels, appended to
/// `moves`.
void edge_slab(const GrowContext& ctx, const Slab& slab, const std::vector<Surface>& surfaces,
               std::span<const double> tolerance, const LayerShifts& shifts,
               const CubeSurfaces& near, const std::vector<std::uint8_t>& near_edge, EdgeScratch& s,
               std::vector<std::pair<std::uint32_t, std::int32_t>>& moves) {
    const CubeIndex& index = ctx.index;
    const std::span<const std::int32_t> labels = ctx.labels;
    const auto mu2 = static_cast<float>(ctx.config.mu * ctx.config.mu);
    if (s.seen.size() != surfaces.size()) s.seen.assign(surfaces.size(), 0);
    for (std::uint32_t c = slab.cube_begin; c < slab.cube_end; ++c) {
        if (!near_edge[c]) continue;
        // The surfaces of the 27 cubes around c, each once.
        cubes_around(index, c, s);
        s.around.clear();
        if (++s.stamp == 0) {  // wrapped: forget every earlier stamp
            std::fill(s.seen.begin(), s.seen.end(), 0);
            s.stamp = 1;
        }
        for (const std::uint32_t k : s.cubes)
            for (const std::int32_t sid : near.of(k)) {
                std::uint32_t& mark = s.seen[static_cast<std::size_t>(sid)];
                if (mark == s.stamp) continue;
                mark = s.stamp;
                s.around.push_back(sid);
            }
        for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
            const std::int32_t own = labels[i];
            if (own < 0) continue;
            const std::size_t scan = ctx.sight.scan_of(i);
            if (scan >= shifts.scans) continue;
            const Vec3f p = index.local_point(i);
            const Vec3d pw = index.world_point(i);
            auto layer_distance = [&](std::int32_t sid) {
                const auto k = static_cast<std::size_t>(sid);
                return std::abs(signed_distance(surfaces[k], pw) - shifts.of(k, scan));
            };
            const Surface& own_surface = surfaces[static_cast<std::size_t>(own)];
            const double own_d = layer_distance(own);
            s.fitting.clear();
            bool any_across = false;
            for (const std::int32_t sid : s.around) {
                if (sid == own) continue;
                const double d = layer_distance(sid);
                if (d < own_d && d <= tolerance[static_cast<std::size_t>(sid)]) {
                    s.fitting.emplace_back(d, sid);
                    any_across =
                        any_across || across(surfaces[static_cast<std::size_t>(sid)], own_surface);
                }
            }
            // Only a surface across the edge can take the point.
            if (!any_across) continue;
            std::sort(s.fitting.begin(), s.fitting.end());
            // Whether surface sid has a member within mu of p.
            auto within = [&](std::int32_t sid) {
                for (const std::uint32_t k : s.cubes) {
                    if (!near.holds(k, sid)) continue;
                    for (std::uint32_t j = index.cube_begin(k); j < index.cube_end(k); ++j)
                        if (labels[j] == sid && (index.local_point(j) - p).squaredNorm() <= mu2)
                            return true;
                }
                return false;
            };
            // The best fit among those within reach; a coplanar one keeps the point where it is.
            for (const auto& [d, sid] : s.fitting) {
                if (!within(sid)) continue;
                if (across(surfaces[static_cast<std::size_t>(sid)], own_surface))
                    moves.emplace_back(i, sid);
                break;
            }
        }
    }
}

}  // namespace

std::uint64_t reassign_at_edges(const GrowContext& ctx, std::span<const Slab> slabs,
                                const std::vector<Surface>& surfaces,
                                std::span<const double> tolerance, int threads,
                                std::span<std::int32_t> labels) {
    if (!ctx.sight.fused() || surfaces.empty()) return 0;
    if (surfaces.size() * ctx.sight.origins.size() > kMaxLayerEntriesPerPoint * labels.size())
        return 0;
    const LayerShifts shifts = layer_shifts(ctx, surfaces, labels, threads);
    const CubeSurfaces near = cube_surfaces(ctx.index, labels, 0, threads);
    std::vector<EdgeScratch> scratch(static_cast<std::size_t>(threads));
    std::vector<std::uint8_t> near_edge(ctx.index.cube_count(), 0);
    ParallelErrors errors;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::size_t k = 0; k < slabs.size(); ++k) {
        errors.run(k, [&] {
            mark_edges(ctx.index, slabs[k], surfaces, near,
                       scratch[static_cast<std::size_t>(omp_get_thread_num())], near_edge);
        });
    }
    errors.rethrow();
    std::vector<std::vector<std::pair<std::uint32_t, std::int32_t>>> moves(slabs.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::size_t k = 0; k < slabs.size(); ++k) {
        errors.run(k, [&] {
            // Filled here and moved: neighbouring slabs' vectors share a cache line.
            std::vector<std::pair<std::uint32_t, std::int32_t>> found;
            edge_slab(ctx, slabs[k], surfaces, tolerance, shifts, near, near_edge,
                      scratch[static_cast<std::size_t>(omp_get_thread_num())], found);
            moves[k] = std::move(found);
        });
    }
    errors.rethrow();
    std::uint64_t moved = 0;
    for (const auto& list : moves)
        for (const auto& [i, sid] : list) {
            labels[i] = sid;
            ++moved;
        }
    return moved;
}

}  // namespace surfgrow::detail
