#include "surfgrow/core/symmetric_eigen.hpp"

namespace surfgrow {

namespace {

/// A unit vector in the null space of the symmetric matrix m (rank <= 2): the longest cross
/// product of its rows. When the rows are parallel to rounding (rank <= 1: collinear points, a
/// repeated smallest eigenvalue) the cross products are noise; then any vector orthogonal to the
/// longest row lies in the null space's span, and the caller's 2x2 step sorts out the rest.
Vec3d null_vector(const Mat3d& m) {
    const Vec3d r0 = m.row(0), r1 = m.row(1), r2 = m.row(2);
    const Vec3d c01 = r0.cross(r1), c02 = r0.cross(r2), c12 = r1.cross(r2);
    const double n01 = c01.squaredNorm(), n02 = c02.squaredNorm(), n12 = c12.squaredNorm();
    const double l0 = r0.squaredNorm(), l1 = r1.squaredNorm(), l2 = r2.squaredNorm();
    const double longest = std::max({l0, l1, l2});
    const double best = std::max({n01, n02, n12});
    if (best > 1e-16 * longest * longest) {  // two rows more than 1e-8 rad from parallel
        if (n01 == best) return c01 / std::sqrt(n01);
        if (n02 == best) return c02 / std::sqrt(n02);
        return c12 / std::sqrt(n12);
    }
    const Vec3d& r = l0 == longest ? r0 : (l1 == longest ? r1 : r2);
    return longest > 0 ? Vec3d(r.unitOrthogonal()) : Vec3d::UnitZ();
}

}  // namespace

SymmetricEigen3 symmetric_eigen(const Mat3d& a) {
    SymmetricEigen3 out;
    const detail::NormalisedCubic c = detail::normalised_cubic(a);
    double lambda = c.scalar ? c.q : c.q + c.p * detail::smallest_normalised_root(c.d);
    Vec3d n = null_vector(a - lambda * Mat3d::Identity());
    lambda = n.dot(a * n);
    n = null_vector(a - lambda * Mat3d::Identity());
    const Vec3d u = n.unitOrthogonal();
    const Vec3d v = n.cross(u);
    const double auu = u.dot(a * u), avv = v.dot(a * v), auv = u.dot(a * v);
    const double mean = 0.5 * (auu + avv);
    const double half = 0.5 * (auu - avv);
    const double radius = std::sqrt(half * half + auv * auv);  // well scaled: no hypot needed
    out.values = {n.dot(a * n), mean - radius, mean + radius};
    out.smallest_vector = n;
    if (out.values[1] < out.values[0]) {
        // n was not the smallest (near-repeated roots): the plane's smaller axis is. Of the 2x2's
        // two row forms of its eigenvector, take the better conditioned.
        const double mu = out.values[1];
        const Eigen::Vector2d e1(auv, mu - auu), e2(mu - avv, auv);
        const Eigen::Vector2d e = e1.squaredNorm() >= e2.squaredNorm() ? e1 : e2;
        out.smallest_vector = e.squaredNorm() > 0 ? Vec3d((e.x() * u + e.y() * v).normalized()) : u;
        std::swap(out.values[0], out.values[1]);
    }
    return out;
}

}  // namespace surfgrow
