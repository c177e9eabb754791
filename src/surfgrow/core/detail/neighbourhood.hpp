// The inner loops of surface growing over runs of the cube index: thin wrappers over the SIMD
// kernels of detail/simd_kernels.hpp, chosen at run time on the CPU found.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/simd_kernels.hpp"
#include "surfgrow/core/plane_fit.hpp"

namespace surfgrow::detail {

static_assert(kKernelLanes <= CubeIndex::kPadding, "cube index padding must cover one SIMD vector");

inline PointArrays arrays_of(const CubeIndex& index) {
    return {index.xs(), index.ys(), index.zs()};
}

/// Calls visit(group, count) over `runs` in groups of at most kKernelChunk points: whole runs
/// while they fit (one kernel call for several short runs), a longer run in pieces that start a
/// whole number of vectors after its begin.
template <class F>
void for_each_chunk(std::span<const CubeIndex::Range> runs, F&& visit) {
    IndexRun group[kKernelChunk];
    std::size_t count = 0;
    std::uint32_t points = 0;
    for (const CubeIndex::Range& run : runs) {
        const std::uint32_t length = run.end - run.begin;
        if (length == 0) continue;
        if (points + length > kKernelChunk && count > 0) {
            visit(static_cast<const IndexRun*>(group), count);
            count = 0;
            points = 0;
        }
        for (std::uint32_t b = run.begin; b < run.end; b += kKernelChunk) {
            const std::uint32_t e = std::min(run.end, b + kKernelChunk);
            if (e - b == kKernelChunk) {
                const IndexRun piece{b, e};
                visit(&piece, std::size_t{1});
            } else {
                group[count++] = {b, e};
                points += e - b;
            }
        }
    }
    if (count > 0) visit(static_cast<const IndexRun*>(group), count);
}

/// The loop of for_each_in_runs_within(); with `labels`, only points whose label is not `skip`.
template <class F>
void runs_within(const CubeIndex& index, std::span<const CubeIndex::Range> runs, const Vec3f& p,
                 float r2, const std::int32_t* labels, std::int32_t skip, F&& f) {
    const KernelTable& k = kernels();
    const PointArrays pts = arrays_of(index);
    const float q[3] = {p.x(), p.y(), p.z()};
    std::uint32_t found[kKernelChunk];
    for_each_chunk(runs, [&](const IndexRun* group, std::size_t count) {
        const std::uint32_t n = k.within(pts, group, count, q, r2, labels, skip, found);
        for (std::uint32_t i = 0; i < n; ++i) f(found[i]);
    });
}

/// Moments (relative to `home`, local coordinates) of the points of `runs` within `radius` of home.
/// Whole vectors are loaded and the lanes past a run's end masked off (the index is padded).
[[nodiscard]] inline Moments gather_moments(const CubeIndex& index,
                                            std::span<const CubeIndex::Range> runs,
                                            const Vec3f& home, float radius) {
    const float h[3] = {home.x(), home.y(), home.z()};
    const RawMoments s =
        kernels().moments(arrays_of(index), runs.data(), runs.size(), h, radius * radius);
    Moments mo;
    mo.n = s.v[0];
    mo.sum = {s.v[1], s.v[2], s.v[3]};
    mo.sum_sq << s.v[4], s.v[5], s.v[6], s.v[5], s.v[7], s.v[8], s.v[6], s.v[8], s.v[9];
    return mo;
}

/// Calls f(j) for every point j of `runs` whose squared distance to `p` (local coordinates) is at
/// most `r2`, in index order: the distance tests in SIMD, the calls for the points that pass.
template <class F>
void for_each_in_runs_within(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                             const Vec3f& p, float r2, F&& f) {
    runs_within(index, runs, p, r2, nullptr, 0, f);
}

/// The same, for the points whose label (`labels`, in index order, readable for
/// CubeIndex::kPadding past the end) is not `label`: the labels compared in SIMD too.
template <class F>
void for_each_other_in_runs_within(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                                   const Vec3f& p, float r2, const std::int32_t* labels,
                                   std::int32_t label, F&& f) {
    runs_within(index, runs, p, r2, labels, label, f);
}

/// Calls f(j, d) for every point j of `runs` within `radius` of `home` and within `tolerance` of
/// the plane through home + `centroid` with unit `normal` (local coordinates, relative to home),
/// d its distance to the plane, in index order: the tests in SIMD, the calls for the points that
/// pass.
template <class F>
void for_each_on_plane(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                       const Vec3f& home, float radius, const Vec3f& normal, const Vec3f& centroid,
                       float tolerance, F&& f) {
    const KernelTable& k = kernels();
    const PointArrays pts = arrays_of(index);
    const float h[3] = {home.x(), home.y(), home.z()};
    const float n[3] = {normal.x(), normal.y(), normal.z()};
    const float offset = normal.dot(centroid);
    std::uint32_t found[kKernelChunk];
    float distance[kKernelChunk];
    for_each_chunk(runs, [&](const IndexRun* group, std::size_t count) {
        const std::uint32_t on = k.on_plane(pts, group, count, h, radius * radius, n, offset,
                                            tolerance, found, distance);
        for (std::uint32_t i = 0; i < on; ++i) f(found[i], distance[i]);
    });
}

/// Sets labels[i] = label for every still unregistered point (labels[i] < 0) of `runs` within
/// `radius` of `home` and within `tolerance` of the plane through home + `centroid` with unit
/// `normal` (local coordinates, relative to home). Returns how many points it registered.
inline std::uint32_t register_points(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                                     const Vec3f& home, float radius, const Vec3f& normal,
                                     const Vec3f& centroid, float tolerance,
                                     std::span<std::int32_t> labels, std::int32_t label) {
    std::uint32_t registered = 0;
    for_each_on_plane(index, runs, home, radius, normal, centroid, tolerance,
                      [&](std::uint32_t j, float) {
                          if (labels[j] >= 0) return;
                          labels[j] = label;
                          ++registered;
                      });
    return registered;
}

/// Gathers FrameSums over the points of `runs` within `radius` of home and within `tolerance` of
/// the plane through `c` (local coordinates relative to home) with unit normal `n` and in-plane
/// unit axes `u`, `v`. Each point's sign along u and v is an FMA weight, not a mask per half.
[[nodiscard]] inline FrameSums gather_frame_sums(const CubeIndex& index,
                                                 std::span<const CubeIndex::Range> runs,
                                                 const Vec3f& home, float radius, const Vec3f& c,
                                                 const Vec3f& u, const Vec3f& v, const Vec3f& n,
                                                 float tolerance) {
    const float h[3] = {home.x(), home.y(), home.z()};
    const float cc[3] = {c.x(), c.y(), c.z()}, uu[3] = {u.x(), u.y(), u.z()};
    const float vv[3] = {v.x(), v.y(), v.z()}, nn[3] = {n.x(), n.y(), n.z()};
    return kernels().frame_sums(arrays_of(index), runs.data(), runs.size(), h, radius * radius, cc,
                                uu, vv, nn, tolerance);
}

/// A point another surface took from its first owner: enough to give it back.
struct TakenPoint {
    std::uint32_t point = 0;
    std::int32_t label = -1;  ///< the owner it was taken from
    float distance = 0;       ///< its distance to that owner's plane
};

/// Best-fit registration: like register_points, but a point already registered to another surface
/// moves to this one when it lies nearer this plane (`distance[j]`, in index order, holds each
/// registered point's distance to its owner's plane). A point near an edge thus ends on the face
/// it belongs to, whichever face grew first. Moved points are appended to `taken` so that an
/// undone surface can give them back. Returns how many unregistered points it registered.
inline std::uint32_t register_best_fit(const CubeIndex& index,
                                       std::span<const CubeIndex::Range> runs, const Vec3f& home,
                                       float radius, const Vec3f& normal, const Vec3f& centroid,
                                       float tolerance, std::span<std::int32_t> labels,
                                       std::span<float> distance, std::int32_t label,
                                       std::vector<TakenPoint>& taken) {
    std::uint32_t registered = 0;
    for_each_on_plane(index, runs, home, radius, normal, centroid, tolerance,
                      [&](std::uint32_t j, float d) {
                          if (labels[j] < 0) {
                              labels[j] = label;
                              distance[j] = d;
                              ++registered;
                          } else if (labels[j] != label && d < distance[j]) {
                              taken.push_back({j, labels[j], distance[j]});
                              labels[j] = label;
                              distance[j] = d;
                          }
                      });
    return registered;
}

}  // namespace surfgrow::detail
