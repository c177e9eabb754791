// The kernels of simd_kernels.hpp, included once per instruction set by simd_kernels_<isa>.cpp,
// which defines SURFGROW_KERNEL_TABLE (the table's name) and is compiled with that set's flags.
// Everything here has internal linkage and uses only std::experimental::simd (always inlined), so
// no function compiled for a wider set can be picked by the linker for a baseline caller.
#pragma once

#include <bit>
#include <experimental/simd>

#include "surfgrow/core/detail/simd_kernels.hpp"

namespace surfgrow::detail {

namespace {

namespace stdx = std::experimental;
using FloatV = stdx::fixed_size_simd<float, kKernelLanes>;
using IntV = stdx::rebind_simd_t<std::int32_t, FloatV>;
constexpr std::uint32_t W = kKernelLanes;

// The helpers below are forced inline: called (not inlined) from a kernel, each would pass its
// vectors through memory, which cost the kernels about 10 % of the growing.
#define SURFGROW_KERNEL_HELPER [[gnu::always_inline]] inline

SURFGROW_KERNEL_HELPER FloatV lanes() {
    return FloatV([](int l) { return static_cast<float>(l); });
}

SURFGROW_KERNEL_HELPER FloatV load(const float* p, std::uint32_t i) {
    return FloatV(p + i, stdx::element_aligned);
}

/// Points i .. i + W - 1 relative to (cx, cy, cz), one vector per axis.
struct Offsets {
    FloatV x, y, z;
    [[nodiscard]] SURFGROW_KERNEL_HELPER FloatV norm2() const { return x * x + y * y + z * z; }
};

SURFGROW_KERNEL_HELPER Offsets offsets(PointArrays p, std::uint32_t i, const FloatV& cx,
                                       const FloatV& cy, const FloatV& cz) {
    return {load(p.x, i) - cx, load(p.y, i) - cy, load(p.z, i) - cz};
}

SURFGROW_KERNEL_HELPER double total(const FloatV& v) {
    return static_cast<double>(stdx::reduce(v));
}

/// The lanes of a mask as bits, lane l in bit l.
template <class Mask>
SURFGROW_KERNEL_HELPER std::uint32_t bits_of(const Mask& m) {
    std::uint32_t bits = 0;
    for (int l = 0; l < static_cast<int>(W); ++l) bits |= static_cast<std::uint32_t>(m[l]) << l;
    return bits;
}

RawMoments moments(PointArrays p, const IndexRun* runs, std::size_t count, const float home[3],
                   float r2) {
    const FloatV lane = lanes();
    const FloatV hx = home[0], hy = home[1], hz = home[2], rr = r2;
    FloatV n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
    for (std::size_t r = 0; r < count; ++r) {
        const IndexRun run = runs[r];
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const auto [dx, dy, dz] = offsets(p, i, hx, hy, hz);
            const auto m =
                (dx * dx + dy * dy + dz * dz <= rr) && (lane < static_cast<float>(run.end - i));
            stdx::where(m, n) += 1.f;
            stdx::where(m, sx) += dx;
            stdx::where(m, sy) += dy;
            stdx::where(m, sz) += dz;
            stdx::where(m, sxx) += dx * dx;
            stdx::where(m, sxy) += dx * dy;
            stdx::where(m, sxz) += dx * dz;
            stdx::where(m, syy) += dy * dy;
            stdx::where(m, syz) += dy * dz;
            stdx::where(m, szz) += dz * dz;
        }
    }
    return {{total(n), total(sx), total(sy), total(sz), total(sxx), total(sxy), total(sxz),
             total(syy), total(syz), total(szz)}};
}

std::uint32_t within(PointArrays pts, const IndexRun* runs, std::size_t count, const float p[3],
                     float r2, const std::int32_t* labels, std::int32_t skip, std::uint32_t* out) {
    const FloatV lane = lanes();
    const FloatV px = p[0], py = p[1], pz = p[2], rr = r2;
    const IntV skipv = skip;
    std::uint32_t found = 0;
    for (std::size_t r = 0; r < count; ++r) {
        const IndexRun run = runs[r];
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const Offsets d = offsets(pts, i, px, py, pz);
            const auto m = (d.norm2() <= rr) && (lane < static_cast<float>(run.end - i));
            if (stdx::none_of(m)) continue;
            std::uint32_t bits = bits_of(m);
            if (labels) bits &= bits_of(IntV(labels + i, stdx::element_aligned) != skipv);
            while (bits) {
                out[found++] = i + static_cast<std::uint32_t>(std::countr_zero(bits));
                bits &= bits - 1;
            }
        }
    }
    return found;
}

std::uint32_t on_plane(PointArrays pts, const IndexRun* runs, std::size_t count,
                       const float home[3], float r2, const float normal[3], float offset,
                       float tolerance, std::uint32_t* out, float* distance) {
    const FloatV lane = lanes();
    const FloatV hx = home[0], hy = home[1], hz = home[2], rr = r2;
    const FloatV nx = normal[0], ny = normal[1], nz = normal[2];
    const FloatV off = offset, tol = tolerance;
    alignas(64) float d[W];
    std::uint32_t found = 0;
    for (std::size_t r = 0; r < count; ++r) {
        const IndexRun run = runs[r];
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const Offsets q = offsets(pts, i, hx, hy, hz);
            const FloatV dist = stdx::abs(q.x * nx + q.y * ny + q.z * nz - off);
            const auto m =
                (q.norm2() <= rr) && (dist <= tol) && (lane < static_cast<float>(run.end - i));
            if (stdx::none_of(m)) continue;
            dist.copy_to(d, stdx::element_aligned);
            std::uint32_t bits = bits_of(m);
            while (bits) {
                const int l = std::countr_zero(bits);
                bits &= bits - 1;
                out[found] = i + static_cast<std::uint32_t>(l);
                distance[found++] = d[l];
            }
        }
    }
    return found;
}

FrameSums frame_sums(PointArrays pts, const IndexRun* runs, std::size_t count, const float home[3],
                     float r2, const float c[3], const float u[3], const float v[3],
                     const float n[3], float tolerance) {
    const FloatV lane = lanes();
    const FloatV hx = home[0], hy = home[1], hz = home[2], rr = r2;
    const FloatV cx = c[0], cy = c[1], cz = c[2], tol = tolerance;
    FloatV all[10], sgn[2][9];
    for (FloatV& x : all) x = 0;
    for (auto& row : sgn)
        for (FloatV& x : row) x = 0;
    for (std::size_t k = 0; k < count; ++k) {
        const IndexRun run = runs[k];
        for (std::uint32_t i = run.begin; i < run.end; i += W) {
            const Offsets q = offsets(pts, i, hx, hy, hz);
            const FloatV dx = q.x - cx, dy = q.y - cy, dz = q.z - cz;
            const FloatV r = dx * n[0] + dy * n[1] + dz * n[2];
            const auto in = (q.norm2() <= rr) && (stdx::abs(r) <= tol) &&
                            (lane < static_cast<float>(run.end - i));
            if (stdx::none_of(in)) continue;
            FloatV w = 0;
            stdx::where(in, w) = 1.f;
            const FloatV qu = dx * u[0] + dy * u[1] + dz * u[2];
            const FloatV qv = dx * v[0] + dy * v[1] + dz * v[2];
            const FloatV t[10] = {w,           w * qu,     w * qv,      w * r,      w * qu * qu,
                                  w * qu * qv, w * qu * r, w * qv * qv, w * qv * r, w * r * r};
            FloatV su = 1, sv = 1;
            stdx::where(qu < FloatV(0.f), su) = -1.f;
            stdx::where(qv < FloatV(0.f), sv) = -1.f;
            for (int k2 = 0; k2 < 10; ++k2) all[k2] += t[k2];
            for (int k2 = 0; k2 < 9; ++k2) {
                sgn[0][k2] += su * t[k2];
                sgn[1][k2] += sv * t[k2];
            }
        }
    }
    FrameSums out;
    for (int k = 0; k < 10; ++k) out.all[k] = total(all[k]);
    for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 9; ++k) out.signed_by[a][k] = total(sgn[a][k]);
    return out;
}

}  // namespace

extern const KernelTable SURFGROW_KERNEL_TABLE;
const KernelTable SURFGROW_KERNEL_TABLE = {SURFGROW_KERNEL_ISA, moments, within, on_plane,
                                           frame_sums};

#undef SURFGROW_KERNEL_HELPER

}  // namespace surfgrow::detail
