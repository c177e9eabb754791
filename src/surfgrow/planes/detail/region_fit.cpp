#include "surfgrow/planes/detail/region_fit.hpp"

#include <cmath>

#include "surfgrow/core/plane_test.hpp"
#include "surfgrow/core/symmetric_eigen.hpp"

namespace surfgrow::detail {

namespace {

constexpr double kCosAcross = 0.70710678118654752;  // cos 45 degrees

}  // namespace

Fit fit_moments(const CentredMoments& m) {
    Fit f;
    if (m.n < 3) return f;
    const Mat3d cov = 0.5 * (m.scatter + m.scatter.transpose()) / m.n;
    const SymmetricEigen3 e = symmetric_eigen(cov);
    f.normal = e.smallest_vector;
    f.eigenvalues = e.values.cwiseMax(0.0);
    f.degenerate = !(f.eigenvalues[1] > 1e-12 * f.eigenvalues[2] && f.eigenvalues[1] > 0);
    return f;
}

void add_normal(Vec3d& sum, const Vec3d& normal, double weight) {
    sum += (normal.dot(sum) >= 0 ? weight : -weight) * normal;
}

void add_judge(Vec3d& judge, const Surface& patch, double weight) {
    if (patch.eigenvalues[1] >= DiskTest{}.min_spread * disk_variance(patch.radius))
        add_normal(judge, patch.normal, weight);
}

Fit region_fit(const CentredMoments& m, const Vec3d& judge) {
    Fit f = fit_moments(m);
    const double norm = judge.norm();
    if (!f.degenerate && norm > 0 && std::abs(f.normal.dot(judge)) < kCosAcross * norm)
        f.degenerate = true;
    return f;
}

}  // namespace surfgrow::detail
