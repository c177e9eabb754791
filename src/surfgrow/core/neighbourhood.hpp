// The two inner loops of surface growing, over runs of the cube index, in SIMD.
#pragma once

#include <bit>
#include <cstdint>
#include <experimental/simd>
#include <span>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/plane_fit.hpp"

namespace surfgrow {

namespace simd = std::experimental;
using FloatV = simd::native_simd<float>;
static_assert(FloatV::size() <= CubeIndex::kPadding,
              "cube index padding must cover one SIMD vector");

/// Moments (relative to `home`, local coordinates) of the points of `runs` within `radius` of home.
/// Whole vectors are loaded and the lanes past a run's end masked off (the index is padded).
[[nodiscard]] inline Moments gather_moments(const CubeIndex& index,
                                            std::span<const CubeIndex::Range> runs,
                                            const Vec3f& home, float radius) {
    constexpr int W = static_cast<int>(FloatV::size());
    const FloatV lane([](int l) { return static_cast<float>(l); });
    const FloatV hx = home.x(), hy = home.y(), hz = home.z(), r2 = radius * radius;
    FloatV n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
    const float* X = index.xs();
    const float* Y = index.ys();
    const float* Z = index.zs();
    for (const CubeIndex::Range& run : runs) {
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const FloatV dx = FloatV(X + i, simd::element_aligned) - hx;
            const FloatV dy = FloatV(Y + i, simd::element_aligned) - hy;
            const FloatV dz = FloatV(Z + i, simd::element_aligned) - hz;
            const auto m =
                (dx * dx + dy * dy + dz * dz <= r2) && (lane < static_cast<float>(run.end - i));
            simd::where(m, n) += 1.f;
            simd::where(m, sx) += dx;
            simd::where(m, sy) += dy;
            simd::where(m, sz) += dz;
            simd::where(m, sxx) += dx * dx;
            simd::where(m, sxy) += dx * dy;
            simd::where(m, sxz) += dx * dz;
            simd::where(m, syy) += dy * dy;
            simd::where(m, syz) += dy * dz;
            simd::where(m, szz) += dz * dz;
        }
    }
    Moments mo;
    auto sum = [](const FloatV& v) { return static_cast<double>(simd::reduce(v)); };
    mo.n = sum(n);
    mo.sum = {sum(sx), sum(sy), sum(sz)};
    mo.sum_sq << sum(sxx), sum(sxy), sum(sxz), sum(sxy), sum(syy), sum(syz), sum(sxz), sum(syz),
        sum(szz);
    return mo;
}

/// The lanes of a SIMD mask as bits, lane l in bit l.
template <class Mask>
[[nodiscard]] inline std::uint32_t lane_bits(const Mask& m) {
    static_assert(Mask::size() <= 32);
    std::uint32_t bits = 0;
    for (int l = 0; l < static_cast<int>(Mask::size()); ++l)
        bits |= static_cast<std::uint32_t>(m[l]) << l;
    return bits;
}

namespace detail {

/// The loop of for_each_in_runs_within(); with `labels`, only points whose label is not `skip`.
template <class F>
void runs_within(const CubeIndex& index, std::span<const CubeIndex::Range> runs, const Vec3f& p,
                 float r2, const std::int32_t* labels, std::int32_t skip, F&& f) {
    using IntV = simd::rebind_simd_t<std::int32_t, FloatV>;
    constexpr int W = static_cast<int>(FloatV::size());
    const FloatV lane([](int l) { return static_cast<float>(l); });
    const FloatV px = p.x(), py = p.y(), pz = p.z(), rr = r2;
    const IntV skipv = skip;
    const float* X = index.xs();
    const float* Y = index.ys();
    const float* Z = index.zs();
    for (const CubeIndex::Range& run : runs) {
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const FloatV dx = FloatV(X + i, simd::element_aligned) - px;
            const FloatV dy = FloatV(Y + i, simd::element_aligned) - py;
            const FloatV dz = FloatV(Z + i, simd::element_aligned) - pz;
            const auto m =
                (dx * dx + dy * dy + dz * dz <= rr) && (lane < static_cast<float>(run.end - i));
            if (simd::none_of(m)) continue;
            std::uint32_t bits = lane_bits(m);
            if (labels) bits &= lane_bits(IntV(labels + i, simd::element_aligned) != skipv);
            while (bits) {
                f(i + static_cast<std::uint32_t>(std::countr_zero(bits)));
                bits &= bits - 1;
            }
        }
    }
}

}  // namespace detail

/// Calls f(j) for every point j of `runs` whose squared distance to `p` (local coordinates) is at
/// most `r2`, in index order: the distance tests in SIMD, the calls for the points that pass.
template <class F>
void for_each_in_runs_within(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                             const Vec3f& p, float r2, F&& f) {
    detail::runs_within(index, runs, p, r2, nullptr, 0, f);
}

/// The same, for the points whose label (`labels`, in index order, readable for
/// CubeIndex::kPadding past the end) is not `label`: the labels compared in SIMD too.
template <class F>
void for_each_other_in_runs_within(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                                   const Vec3f& p, float r2, const std::int32_t* labels,
                                   std::int32_t label, F&& f) {
    detail::runs_within(index, runs, p, r2, labels, label, f);
}

/// Calls f(j, d) for every point j of `runs` within `radius` of `home` and within `tolerance` of
/// the plane through home + `centroid` with unit `normal` (local coordinates, relative to home),
/// d its distance to the plane, in index order: the tests in SIMD, the calls for the points that
/// pass.
template <class F>
void for_each_on_plane(const CubeIndex& index, std::span<const CubeIndex::Range> runs,
                       const Vec3f& home, float radius, const Vec3f& normal, const Vec3f& centroid,
                       float tolerance, F&& f) {
    constexpr int W = static_cast<int>(FloatV::size());
    const FloatV lane([](int l) { return static_cast<float>(l); });
    const FloatV hx = home.x(), hy = home.y(), hz = home.z(), r2 = radius * radius;
    const FloatV nx = normal.x(), ny = normal.y(), nz = normal.z();
    const FloatV off = normal.dot(centroid), tol = tolerance;
    const float* X = index.xs();
    const float* Y = index.ys();
    const float* Z = index.zs();
    alignas(64) float d[FloatV::size()];
    for (const CubeIndex::Range& run : runs) {
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const FloatV dx = FloatV(X + i, simd::element_aligned) - hx;
            const FloatV dy = FloatV(Y + i, simd::element_aligned) - hy;
            const FloatV dz = FloatV(Z + i, simd::element_aligned) - hz;
            const FloatV dist = simd::abs(dx * nx + dy * ny + dz * nz - off);
            const auto m = (dx * dx + dy * dy + dz * dz <= r2) && (dist <= tol) &&
                           (lane < static_cast<float>(run.end - i));
            if (simd::none_of(m)) continue;
            dist.copy_to(d, simd::element_aligned);
            std::uint32_t bits = lane_bits(m);
            while (bits) {
                const int l = std::countr_zero(bits);
                bits &= bits - 1;
                f(i + static_cast<std::uint32_t>(l), d[l]);
            }
        }
    }
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

/// A neighbourhood's inliers in a plane's own frame: q = (u, v, r), the coordinates along two
/// in-plane axes and the normal relative to a point c of the plane. `all` holds, over the inliers,
/// the sums of 1, u, v, r, uu, uv, ur, vv, vr, rr; `signed_by[a]` the same sums (but rr) with
/// each point weighted by the sign of its coordinate along axis a (u or v): the two halves of the
/// neighbourhood across that axis are (all + signed) / 2 and (all - signed) / 2.
struct FrameSums {
    double all[10] = {};
    double signed_by[2][9] = {};
};

/// Gathers FrameSums over the points of `runs` within `radius` of home and within `tolerance` of
/// the plane through `c` (local coordinates relative to home) with unit normal `n` and in-plane
/// unit axes `u`, `v`. Each point's sign along u and v is an FMA weight, not a mask per half.
[[nodiscard]] inline FrameSums gather_frame_sums(const CubeIndex& index,
                                                 std::span<const CubeIndex::Range> runs,
                                                 const Vec3f& home, float radius, const Vec3f& c,
                                                 const Vec3f& u, const Vec3f& v, const Vec3f& n,
                                                 float tolerance) {
    constexpr int W = static_cast<int>(FloatV::size());
    const FloatV lane([](int l) { return static_cast<float>(l); });
    const FloatV hx = home.x(), hy = home.y(), hz = home.z(), r2 = radius * radius;
    const FloatV cx = c.x(), cy = c.y(), cz = c.z(), tol = tolerance;
    FloatV all[10], sgn[2][9];
    for (FloatV& x : all) x = 0;
    for (auto& row : sgn)
        for (FloatV& x : row) x = 0;
    const float* X = index.xs();
    const float* Y = index.ys();
    const float* Z = index.zs();
    for (const CubeIndex::Range& run : runs) {
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const FloatV px = FloatV(X + i, simd::element_aligned) - hx;
            const FloatV py = FloatV(Y + i, simd::element_aligned) - hy;
            const FloatV pz = FloatV(Z + i, simd::element_aligned) - hz;
            const FloatV dx = px - cx, dy = py - cy, dz = pz - cz;
            const FloatV r = dx * n.x() + dy * n.y() + dz * n.z();
            const auto in = (px * px + py * py + pz * pz <= r2) && (simd::abs(r) <= tol) &&
                            (lane < static_cast<float>(run.end - i));
            if (simd::none_of(in)) continue;
            FloatV w = 0;
            simd::where(in, w) = 1.f;
            const FloatV qu = dx * u.x() + dy * u.y() + dz * u.z();
            const FloatV qv = dx * v.x() + dy * v.y() + dz * v.z();
            const FloatV t[10] = {w,           w * qu,     w * qv,      w * r,      w * qu * qu,
                                  w * qu * qv, w * qu * r, w * qv * qv, w * qv * r, w * r * r};
            FloatV su = 1, sv = 1;
            simd::where(qu < FloatV(0.f), su) = -1.f;
            simd::where(qv < FloatV(0.f), sv) = -1.f;
            for (int k = 0; k < 10; ++k) all[k] += t[k];
            for (int k = 0; k < 9; ++k) {
                sgn[0][k] += su * t[k];
                sgn[1][k] += sv * t[k];
            }
        }
    }
    FrameSums out;
    for (int k = 0; k < 10; ++k) out.all[k] = static_cast<double>(simd::reduce(all[k]));
    for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 9; ++k)
            out.signed_by[a][k] = static_cast<double>(simd::reduce(sgn[a][k]));
    return out;
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

}  // namespace surfgrow
