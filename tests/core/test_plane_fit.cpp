#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "surfgrow/core/plane_fit.hpp"

namespace surfgrow {
namespace {

constexpr double kDeg = M_PI / 180.0;

Moments moments_of(const std::vector<Vec3d>& pts, const Vec3d& ref) {
    Moments m;
    for (const auto& p : pts) m.add(p - ref);
    return m;
}

// Points uniformly in a disk of radius r on the plane through c with normal n, with Gaussian
// noise sigma along the normal.
std::vector<Vec3d> noisy_disk(const Vec3d& c, const Vec3d& n, double r, double sigma, int count,
                              std::mt19937_64& rng) {
    const Vec3d u = n.unitOrthogonal(), v = n.cross(u);
    std::uniform_real_distribution<double> uni(-r, r);
    std::normal_distribution<double> g(0.0, sigma);
    std::vector<Vec3d> pts;
    while (static_cast<int>(pts.size()) < count) {
        const double a = uni(rng), b = uni(rng);
        if (a * a + b * b > r * r) continue;
        pts.push_back(c + a * u + b * v + (sigma > 0 ? g(rng) : 0.0) * n);
    }
    return pts;
}

// Normal error on random noisy disks, against the theory: for N points uniform in a disk of
// radius r (in-plane spread r/2) with normal noise sigma, the normal's angular error is about
// sigma / (r/2 * sqrt(N)) per axis, so its magnitude has a median near 1.18 times that.
std::vector<double> disk_normal_errors(double r, double sigma, int count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> dir(-1, 1);
    std::vector<double> errors;
    while (errors.size() < 500) {
        Vec3d n(dir(rng), dir(rng), dir(rng));
        if (n.norm() < 0.1) continue;
        n.normalize();
        const Vec3d c(dir(rng), dir(rng), dir(rng));
        const auto pts = noisy_disk(c, n, r, sigma, count, rng);
        const PlaneFit fit = fit_plane(moments_of(pts, pts.front()));
        EXPECT_NEAR(fit.normal.norm(), 1.0, 1e-12);
        EXPECT_LT(std::abs(n.dot(fit.centroid + pts.front() - c)),
                  4 * sigma / std::sqrt(count) + 1e-12);
        errors.push_back(axis_angle_between(fit.normal, n));
    }
    std::sort(errors.begin(), errors.end());
    return errors;
}

TEST(PlaneFit, RecoversNormalOfNoisyPlanesWellUnderOneDegree) {
    // A well-sampled 50 mm patch, 200 points, 0.5 mm noise: theory says ~0.1 degree.
    const auto errors = disk_normal_errors(0.05, 0.0005, 200, 7);
    EXPECT_LT(errors[errors.size() / 2], 0.2 * kDeg);
    EXPECT_LT(errors.back(), 1.0 * kDeg);
}

TEST(PlaneFit, NormalErrorMatchesTheoryAtThePapersScale) {
    // mu = 12 mm, 40 points, 0.5 mm noise: theory ~0.95 degree median.
    const double r = 0.012, sigma = 0.0005;
    const int count = 40;
    const double theory_median = 1.18 * sigma / (r / 2 * std::sqrt(count));
    const auto errors = disk_normal_errors(r, sigma, count, 8);
    EXPECT_LT(errors[errors.size() / 2], 1.3 * theory_median);
    EXPECT_GT(errors[errors.size() / 2], 0.7 * theory_median);
}

TEST(PlaneFit, ExactPlaneHasZeroSmallestEigenvalueAndExactNormal) {
    std::mt19937_64 rng(8);
    const Vec3d n = Vec3d(1, 2, 3).normalized();
    const auto pts = noisy_disk(Vec3d(100, -50, 3), n, 0.012, 0.0, 30, rng);
    const PlaneFit fit = fit_plane(moments_of(pts, pts[3]));
    EXPECT_LT(axis_angle_between(fit.normal, n), 1e-6);
    EXPECT_LT(fit.eigenvalues[0], 1e-12);
    EXPECT_GT(fit.eigenvalues[1], 1e-6);
}

TEST(PlaneFit, EigenvaluesMatchIterativeSolver) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-0.01, 0.01);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<Vec3d> pts(25);
        const Vec3d scale(1.0, 0.3 + 0.7 * std::abs(u(rng)) * 100, 0.01 + std::abs(u(rng)) * 10);
        for (auto& p : pts) p = Vec3d(u(rng), u(rng), u(rng)).cwiseProduct(scale);
        const Moments m = moments_of(pts, Vec3d::Zero());
        const PlaneFit fit = fit_plane(m);
        const Vec3d mean = m.sum / m.n;
        const Mat3d cov = m.sum_sq / m.n - mean * mean.transpose();
        Eigen::SelfAdjointEigenSolver<Mat3d> ref(cov);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(fit.eigenvalues[k], std::max(0.0, ref.eigenvalues()[k]),
                        1e-9 * ref.eigenvalues()[2] + 1e-15);
        EXPECT_LT(axis_angle_between(fit.normal, ref.eigenvectors().col(0)), 1e-4);
    }
}

TEST(PlaneFit, PlaneTestFollowsEquationTwo) {
    EXPECT_TRUE(is_planar(Vec3d(0.0, 1.0, 2.0), 4.0));
    EXPECT_TRUE(is_planar(Vec3d(0.24, 1.0, 2.0), 4.0));
    EXPECT_FALSE(is_planar(Vec3d(0.25, 1.0, 2.0), 4.0));  // strict inequality
    EXPECT_FALSE(is_planar(Vec3d(0.5, 0.6, 2.0), 4.0));   // an edge: two comparable spreads
    EXPECT_FALSE(is_planar(Vec3d(0.0, 0.0, 2.0), 4.0));   // a line: mid = 0
    EXPECT_FALSE(is_planar(Vec3d(0.0, 0.0, 0.0), 4.0));   // a point
}

TEST(PlaneFit, CollinearPointsAreNotAPlane) {
    std::vector<Vec3d> pts;
    for (int i = 0; i < 20; ++i) pts.emplace_back(0.001 * i, 0.002 * i, -0.0005 * i);
    const PlaneFit fit = fit_plane(moments_of(pts, pts[0]));
    EXPECT_FALSE(is_planar(fit.eigenvalues, 1.5));
}

}  // namespace
}  // namespace surfgrow
