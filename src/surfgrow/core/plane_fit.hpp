// Principal component analysis of a neighbourhood: the plane test of paper eq. (2).
#pragma once

#include <algorithm>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/moments.hpp"
#include "surfgrow/core/symmetric_eigen.hpp"

namespace surfgrow {

/// The result of PCA on a neighbourhood.
struct PlaneFit {
    Vec3d centroid = Vec3d::Zero();     ///< in the frame of the moments' reference point
    Vec3d normal = Vec3d::UnitZ();      ///< eigenvector of the smallest eigenvalue (unit)
    Vec3d eigenvalues = Vec3d::Zero();  ///< ascending
};

/// Covariance of the moments' points (n >= 1).
[[nodiscard]] inline Mat3d covariance(const Moments& m) {
    const Vec3d mean = m.sum / m.n;
    Mat3d cov = m.sum_sq / m.n - mean * mean.transpose();
    return 0.5 * (cov + cov.transpose());
}

/// PCA of the moments' points by the closed-form solver (symmetric_eigen.hpp), in double.
/// Requires m.n >= 1.
[[nodiscard]] inline PlaneFit fit_plane(const Moments& m) {
    const SymmetricEigen3 e = symmetric_eigen(covariance(m));
    return {m.sum / m.n, e.smallest_vector, e.values.cwiseMax(0.0)};  // rounding can dip below 0
}

/// A unit eigenvector of symmetric `a` for its eigenvalue `value`: the longest cross product of
/// two rows of a - value I (they span the orthogonal complement). Any unit vector orthogonal to
/// `orthogonal_to` when the eigenvalue is repeated.
[[nodiscard]] inline Vec3d eigenvector_of(const Mat3d& a, double value,
                                          const Vec3d& orthogonal_to) {
    const Mat3d b = a - value * Mat3d::Identity();
    const Vec3d c[3] = {b.row(0).cross(b.row(1)), b.row(0).cross(b.row(2)),
                        b.row(1).cross(b.row(2))};
    const Vec3d* best = &c[0];
    for (const Vec3d& v : c)
        if (v.squaredNorm() > best->squaredNorm()) best = &v;
    if (best->squaredNorm() > 1e-24 * std::max(b.squaredNorm() * b.squaredNorm(), 1e-300))
        return best->normalized();
    return orthogonal_to.unitOrthogonal();
}

/// True when the cubic's eigenvalues (rough_eigenvalues, ascending) already show, with a margin
/// far above their error, that the neighbourhood fails eq. (2): the full decomposition can be
/// skipped.
[[nodiscard]] inline bool clearly_not_planar(const Vec3d& rough, double alpha) {
    return rough[0] * alpha > rough[1] * (1 + 1e-6) + 1e-6 * rough[2];
}

/// Paper eq. (2): the neighbourhood is a plane when min(lambda) < mid(lambda) / alpha.
/// A line or a single point is never a plane: mid(lambda) must stand above rounding noise
/// (1e-10 of the largest), or collinear points would pass on round-off alone.
[[nodiscard]] inline bool is_planar(const Vec3d& ascending_eigenvalues, double alpha) {
    const Vec3d& e = ascending_eigenvalues;
    return e[0] * alpha < e[1] && e[1] > 1e-10 * e[2];
}

}  // namespace surfgrow
