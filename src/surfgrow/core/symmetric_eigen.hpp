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
///
/// Defined out of line, in one translation unit: an inline copy would be compiled into every
/// caller's object, each contracted to fused multiply-adds its own way, and the linker would keep
/// whichever copy it met first, so the last bits of normals would depend on what a program links.
[[nodiscard]] SymmetricEigen3 symmetric_eigen(const Mat3d& a);

}  // namespace surfgrow
