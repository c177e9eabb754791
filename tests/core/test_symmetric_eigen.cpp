#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "surfgrow/core/symmetric_eigen.hpp"

namespace surfgrow {
namespace {

// Random symmetric matrices with a chosen spectrum, including repeated and tiny eigenvalues.
Mat3d with_spectrum(const Vec3d& values, std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    const Eigen::Quaterniond q = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    const Mat3d r = q.toRotationMatrix();
    return r * values.asDiagonal() * r.transpose();
}

TEST(SymmetricEigen, MatchesIterativeSolverOverWideSpectra) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-12, 0);
    for (int trial = 0; trial < 5000; ++trial) {
        Vec3d v(std::pow(10.0, u(rng)), std::pow(10.0, u(rng)), std::pow(10.0, u(rng)));
        if (trial % 5 == 0) v[1] = v[0];  // repeated
        if (trial % 7 == 0) v[0] = 0;     // exact plane
        const Mat3d a = with_spectrum(v, rng);
        Eigen::SelfAdjointEigenSolver<Mat3d> ref(a);
        const SymmetricEigen3 res = symmetric_eigen(a);
        const Vec3d& e = res.values;
        const double scale = ref.eigenvalues().cwiseAbs().maxCoeff();
        // To rounding when the smallest eigenvalue is simple; sqrt(eps) at a repeated smallest.
        const bool simple = ref.eigenvalues()[1] - ref.eigenvalues()[0] > 1e-6 * scale;
        const double tol = (simple ? 1e-14 : 1e-7) * scale;
        for (int k = 0; k < 3; ++k)
            ASSERT_NEAR(e[k], ref.eigenvalues()[k], tol) << trial << " " << k;
        ASSERT_LE(e[0], e[1]);
        ASSERT_LE(e[1], e[2]);
        // The smallest eigenvector within the Davis-Kahan bound: angle <= c eps |A| / gap, so a
        // well-separated eigenvalue gets an eigenvector accurate to rounding.
        const Vec3d& n = res.smallest_vector;
        EXPECT_NEAR(n.norm(), 1.0, 1e-12);
        const double gap = ref.eigenvalues()[1] - ref.eigenvalues()[0];
        const double bound = 1e-13 * scale / std::max(gap, 1e-300);
        EXPECT_LT((a * n - e[0] * n).norm(),
                  (simple ? 1e-14 * scale + bound * scale : 1e-7 * scale))
            << trial;
        if (simple) {
            EXPECT_LT(axis_angle_between(n, ref.eigenvectors().col(0)), bound + 1e-14) << trial;
        }
    }
}

TEST(SymmetricEigen, RoughEigenvaluesMatchTheIterativeSolver) {
    // The quick plane test's eigenvalues: Newton's smallest root and the deflated quadratic.
    // Accurate to 1e-10 |A| where the roots are simple, ~sqrt(eps) where two coincide: the
    // smallest pair (collinear points: Newton converges linearly there) or the largest (a disk).
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-8, 0);
    for (int trial = 0; trial < 5000; ++trial) {
        Vec3d v(std::pow(10.0, u(rng)), std::pow(10.0, u(rng)), std::pow(10.0, u(rng)));
        if (trial % 5 == 0) v[1] = v[0];
        if (trial % 5 == 1) v[1] = v[2];
        if (trial % 7 == 0) v[0] = 0;
        const Mat3d a = with_spectrum(v, rng);
        const Vec3d ref = Eigen::SelfAdjointEigenSolver<Mat3d>(a).eigenvalues();
        const Vec3d e = rough_eigenvalues(a);
        const double scale = ref.cwiseAbs().maxCoeff();
        const bool simple = ref[1] - ref[0] > 1e-6 * scale && ref[2] - ref[1] > 1e-6 * scale;
        for (int k = 0; k < 3; ++k)
            ASSERT_NEAR(e[k], ref[k], (simple ? 1e-10 : 1e-7) * scale) << trial << " " << k;
    }
    EXPECT_EQ(rough_eigenvalues(Mat3d::Zero()), Vec3d::Zero());
    EXPECT_EQ(rough_eigenvalues(4.0 * Mat3d::Identity()), Vec3d::Constant(4.0));
}

TEST(SymmetricEigen, DegenerateMatrices) {
    EXPECT_EQ(symmetric_eigen(Mat3d::Zero()).values, Vec3d::Zero());
    EXPECT_EQ(symmetric_eigen(2.5 * Mat3d::Identity()).values, Vec3d::Constant(2.5));
    const Vec3d diag = symmetric_eigen(Vec3d(3, 1, 2).asDiagonal().toDenseMatrix()).values;
    EXPECT_NEAR(diag[0], 1, 1e-15);
    EXPECT_NEAR(diag[1], 2, 1e-15);
    EXPECT_NEAR(diag[2], 3, 1e-15);
    // Rank one (collinear points): two zero eigenvalues.
    const Vec3d d = Vec3d(1, 2, 3).normalized();
    const Vec3d e = symmetric_eigen(d * d.transpose()).values;
    EXPECT_NEAR(e[0], 0, 1e-15);
    EXPECT_NEAR(e[1], 0, 1e-15);
    EXPECT_NEAR(e[2], 1, 1e-15);
    // The null vector of a rank-two matrix (an exact plane) is its normal.
    const Vec3d n = Vec3d(0.3, -0.2, 0.9).normalized();
    const Mat3d plane = Mat3d::Identity() - n * n.transpose();
    EXPECT_LT(axis_angle_between(symmetric_eigen(plane).smallest_vector, n), 1e-12);
    EXPECT_NEAR(symmetric_eigen(plane).values[0], 0.0, 1e-15);
    EXPECT_TRUE(symmetric_eigen(Mat3d::Zero()).smallest_vector.allFinite());
}

}  // namespace
}  // namespace surfgrow
