// Principal component analysis of a neighbourhood: the plane test of paper eq. (2).
#pragma once

#include <Eigen/Eigenvalues>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// First and second moments of a point set, relative to a reference point (the home point).
/// Relative sums keep float accumulation accurate: every offset is at most the radius.
struct Moments {
    double n = 0;
    Vec3d sum = Vec3d::Zero();
    Mat3d sum_sq = Mat3d::Zero();  ///< sum of d d^T (symmetric)

    void add(const Vec3d& d) {
        n += 1;
        sum += d;
        sum_sq += d * d.transpose();
    }
};

/// The result of PCA on a neighbourhood.
struct PlaneFit {
    Vec3d centroid = Vec3d::Zero();     ///< in the frame of the moments' reference point
    Vec3d normal = Vec3d::UnitZ();      ///< eigenvector of the smallest eigenvalue (unit)
    Vec3d eigenvalues = Vec3d::Zero();  ///< ascending
};

/// Covariance eigen-decomposition by Eigen's closed-form 3x3 solver (computeDirect), in double.
/// Requires m.n >= 1.
[[nodiscard]] inline PlaneFit fit_plane(const Moments& m) {
    PlaneFit fit;
    const Vec3d mean = m.sum / m.n;
    Mat3d cov = m.sum_sq / m.n - mean * mean.transpose();
    cov = 0.5 * (cov + cov.transpose());
    Eigen::SelfAdjointEigenSolver<Mat3d> solver;
    solver.computeDirect(cov);
    fit.centroid = mean;
    fit.eigenvalues = solver.eigenvalues().cwiseMax(0.0);  // ascending; rounding can dip below 0
    fit.normal = solver.eigenvectors().col(0).normalized();
    return fit;
}

/// Paper eq. (2): the neighbourhood is a plane when min(lambda) < mid(lambda) / alpha.
/// A line or a single point (mid = 0) is never a plane.
[[nodiscard]] inline bool is_planar(const Vec3d& ascending_eigenvalues, double alpha) {
    return ascending_eigenvalues[0] * alpha < ascending_eigenvalues[1];
}

}  // namespace surfgrow
