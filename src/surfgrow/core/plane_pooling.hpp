// Refining patch normals by pooling the moments of adjacent coplanar patches.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/plane_fit.hpp"

namespace surfgrow {

/// A patch as pooling sees it: its home point, its own fit, its moments about the home point.
struct PoolablePatch {
    Vec3d home;
    Vec3d centroid;     ///< absolute
    Vec3d normal;       ///< unit, either sign
    double lambda_min;  ///< smallest covariance eigenvalue: the patch's noise variance
    Moments moments;    ///< about `home`
};

struct PoolingConfig {
    double radius = 0.024;       ///< pool patches whose home points lie within this distance
    double max_angle = 0.26;     ///< and whose normals differ by at most this (radians)
    double min_offset = 0.0012;  ///< floor of the coplanarity test (noise-free data)
    double max_offset = 0.006;   ///< ceiling of the coplanarity test
    int threads = 1;
};

/// For each patch, the normal of the least-squares plane through its own neighbourhood and those
/// of the neighbouring patches that lie in the same plane: normals within max_angle and each
/// centroid within 3 sigma (the larger patch noise, clamped to [min_offset, max_offset]) of the
/// other's plane. Patches across an edge or on the far side of a thin plate are never pooled.
/// With k coplanar neighbours the normal's noise drops by about sqrt(k). Returns unit normals
/// with the sign of the patch's own normal. Deterministic for any thread count.
[[nodiscard]] std::vector<Vec3d> pool_normals(std::span<const PoolablePatch> patches,
                                              const PoolingConfig& config);

/// The same; `lone[k]` is set to 1 where patch k has at least `min_neighbours` patches within the
/// radius but none in its plane: a patch that disagrees with everything around it, such as a fit
/// tilted across an edge or a depth edge's mixed pixels.
[[nodiscard]] std::vector<Vec3d> pool_normals(std::span<const PoolablePatch> patches,
                                              const PoolingConfig& config,
                                              std::vector<std::uint8_t>& lone, int min_neighbours);

}  // namespace surfgrow
