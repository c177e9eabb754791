// Closed-form eigen-decomposition of a symmetric 3x3 matrix (covariances), accurate to rounding.
#pragma once

#include <algorithm>
#include <cmath>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// Ascending eigenvalues and the unit eigenvector of the smallest one.
struct SymmetricEigen3 {
    Vec3d values = Vec3d::Zero();
    Vec3d smallest_vector = Vec3d::UnitZ();
};

namespace detail {

/// Eigenvalues by the trigonometric solution of the characteristic cubic (Smith 1961): cheap,
/// but at a repeated root only accurate to sqrt(epsilon), hence the refinement below.
inline Vec3d cubic_eigenvalues(const Mat3d& a) {
    const double p1 = a(0, 1) * a(0, 1) + a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2);
    const double q = a.trace() / 3.0;
    const double d0 = a(0, 0) - q, d1 = a(1, 1) - q, d2 = a(2, 2) - q;
    const double p2 = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * p1;
    if (p2 <= 1e-300) return Vec3d::Constant(q);  // a multiple of the identity
    const double p = std::sqrt(p2 / 6.0);
    const double b00 = d0 / p, b11 = d1 / p, b22 = d2 / p;
    const double b01 = a(0, 1) / p, b02 = a(0, 2) / p, b12 = a(1, 2) / p;
    const double det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
                       b02 * (b01 * b12 - b11 * b02);
    const double phi = std::acos(std::clamp(det / 2.0, -1.0, 1.0)) / 3.0;
    const double largest = q + 2.0 * p * std::cos(phi);
    const double smallest = q + 2.0 * p * std::cos(phi + 2.0 * M_PI / 3.0);
    return {smallest, 3.0 * q - largest - smallest, largest};
}

/// A unit vector in the null space of the symmetric matrix m (rank <= 2): the longest cross
/// product of its rows. When the rows are parallel to rounding (rank <= 1: collinear points, a
/// repeated smallest eigenvalue) the cross products are noise; then any vector orthogonal to the
/// longest row lies in the null space's span, and the caller's 2x2 step sorts out the rest.
inline Vec3d null_vector(const Mat3d& m) {
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

}  // namespace detail

/// Eigenvalues of a symmetric 3x3 matrix from the cubic alone, ascending: about a third of the
/// cost of symmetric_eigen(), accurate to ~1e-8 |A| (less at repeated roots). For quick
/// rejections; decisions at the margin go to symmetric_eigen().
[[nodiscard]] inline Vec3d rough_eigenvalues(const Mat3d& a) {
    Vec3d e = detail::cubic_eigenvalues(a);
    std::sort(e.data(), e.data() + 3);
    return e;
}

/// Eigen-decomposition of a symmetric 3x3 matrix in closed form, a few hundred flops.
///
/// The cubic gives the smallest eigenvalue roughly; its eigenvector n is the null space of
/// (A - lambda I), refined once at the Rayleigh quotient; then lambda_min = n'An (error quadratic
/// in n's) and the other two are those of A on the plane orthogonal to n, a 2x2 problem with a
/// stable closed form. Accuracy: to rounding when the smallest eigenvalue is simple (every plane
/// patch: the eigenvector within the Davis-Kahan bound ~eps |A| / gap); about sqrt(eps) |A| for
/// the eigenvalues when the two smallest coincide (collinear points, isotropic blobs), cases
/// which the plane test of eq. (2) rejects anyway.
[[nodiscard]] inline SymmetricEigen3 symmetric_eigen(const Mat3d& a) {
    SymmetricEigen3 out;
    const Vec3d rough = detail::cubic_eigenvalues(a);
    double lambda = std::min({rough[0], rough[1], rough[2]});
    Vec3d n = detail::null_vector(a - lambda * Mat3d::Identity());
    lambda = n.dot(a * n);
    n = detail::null_vector(a - lambda * Mat3d::Identity());
    const Vec3d u = n.unitOrthogonal();
    const Vec3d v = n.cross(u);
    const double auu = u.dot(a * u), avv = v.dot(a * v), auv = u.dot(a * v);
    const double mean = 0.5 * (auu + avv);
    const double radius = std::hypot(0.5 * (auu - avv), auv);
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
