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

/// Which patches pooling marks as lone: patches that disagree with what is around them.
struct LoneRule {
    int min_neighbours = 0;  ///< 0: none is marked; else only patches with this many within reach
    /// Also marked: a patch whose plane (its points and its coplanar neighbours') holds less than
    /// this share of the points of the patches around it in other planes; 0 turns this off.
    double minority_share = 0;
};

/// The same; `lone[k]` is set to 1 where patch k has at least `rule.min_neighbours` patches
/// within the radius and none in its plane (a fit tilted across an edge), or its plane is a
/// minority beside other planes (`rule.minority_share`: a depth edge's mixed pixels, one beam
/// footprint wide between two faces). `lone` is left empty when `rule.min_neighbours` is 0.
[[nodiscard]] std::vector<Vec3d> pool_normals(std::span<const PoolablePatch> patches,
                                              const PoolingConfig& config,
                                              std::vector<std::uint8_t>& lone,
                                              const LoneRule& rule);

}  // namespace surfgrow
