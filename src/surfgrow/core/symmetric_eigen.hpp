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

/// The eigenvalues of a symmetric 3x3 matrix A are q + p * beta, where q = trace / 3 and the
/// betas, in [-2, 2], are the roots of beta^3 - 3 beta - d with d = det((A - q I) / p) in [-2, 2]
/// (Smith 1961). `scalar`: A is a multiple of the identity (p = 0).
struct NormalisedCubic {
    double q = 0, p = 0, d = 0;
    bool scalar = false;
};

inline NormalisedCubic normalised_cubic(const Mat3d& a) {
    NormalisedCubic c;
    const double p1 = a(0, 1) * a(0, 1) + a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2);
    c.q = a.trace() / 3.0;
    const double d0 = a(0, 0) - c.q, d1 = a(1, 1) - c.q, d2 = a(2, 2) - c.q;
    const double p2 = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * p1;
    if (p2 <= 1e-300) {
        c.scalar = true;
        return c;
    }
    c.p = std::sqrt(p2 / 6.0);
    const double b00 = d0 / c.p, b11 = d1 / c.p, b22 = d2 / c.p;
    const double b01 = a(0, 1) / c.p, b02 = a(0, 2) / c.p, b12 = a(1, 2) / c.p;
    c.d = std::clamp(b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
                         b02 * (b01 * b12 - b11 * b02),
                     -2.0, 2.0);
    return c;
}

/// The smallest root of beta^3 - 3 beta - d, |d| <= 2, by Newton's method from -2: the cubic is
/// increasing and concave left of -1, so the iterates climb monotonically to the root,
/// quadratically where it is simple (every plane patch; a few steps), linearly where it is double
/// (d = 2: collinear points, which the 2x2 step of symmetric_eigen() sorts out). Cheaper than the
/// trigonometric solution's acos and cos.
inline double smallest_normalised_root(double d) {
    double b = -2.0;
    for (int k = 0; k < 64; ++k) {
        const double f = (b * b - 3.0) * b - d;
        const double slope = 3.0 * (b * b - 1.0);
        if (!(f < 0) || !(slope > 0)) break;  // at the root, to rounding
        const double step = f / slope;
        b -= step;
        if (-step <= 1e-15) break;
    }
    return std::min(b, -1.0);
}

/// All three eigenvalues, ascending: the smallest root, then the other two from the quadratic
/// left after dividing it out, beta^2 + r beta + r^2 - 3. At a repeated root only accurate to
/// sqrt(epsilon), hence the refinement in symmetric_eigen().
inline Vec3d cubic_eigenvalues(const Mat3d& a) {
    const NormalisedCubic c = normalised_cubic(a);
    if (c.scalar) return Vec3d::Constant(c.q);
    const double r = smallest_normalised_root(c.d);
    const double h = 0.5 * std::sqrt(std::max(0.0, 12.0 - 3.0 * r * r));
    return {c.q + c.p * r, c.q + c.p * (-0.5 * r - h), c.q + c.p * (-0.5 * r + h)};
}

}  // namespace detail

/// Eigenvalues of a symmetric 3x3 matrix from the cubic alone, ascending: about a third of the
/// cost of symmetric_eigen(), accurate to 1e-10 |A| (1e-7 at repeated roots; tested). For quick
/// rejections; decisions at the margin go to symmetric_eigen().
[[nodiscard]] inline Vec3d rough_eigenvalues(const Mat3d& a) {
    Vec3d e = detail::cubic_eigenvalues(a);
    std::sort(e.data(), e.data() + 3);  // in order already, but for rounding
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
