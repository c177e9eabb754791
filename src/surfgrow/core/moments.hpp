// The first and second moments of a point set, the sums every plane fit in surfgrow starts from:
// raw sums about a reference point (what the neighbourhood kernels accumulate) and the centred
// form whose merge is exact (what bound planes pool regions with).
#pragma once

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
        // d d^T entry by entry: the same products and sums as the matrix expression, which
        // Eigen evaluated out of line (4 % of the bound planes' time, called per point).
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) sum_sq(i, j) += d[i] * d[j];
    }
};

/// The moments of a set about `from`, re-expressed about `to` (d' = d + (from - to)).
[[nodiscard]] inline Moments moments_about(const Moments& m, const Vec3d& from, const Vec3d& to) {
    const Vec3d t = from - to;
    Moments out;
    out.n = m.n;
    out.sum = m.sum + m.n * t;
    out.sum_sq = m.sum_sq + m.sum * t.transpose() + t * m.sum.transpose() + m.n * t * t.transpose();
    return out;
}

/// Count, mean and scatter matrix about the mean: merging two sets is exact and stable (Chan et
/// al.), so a region's plane is the least-squares fit of the union of its parts' points.
struct CentredMoments {
    double n = 0;
    Vec3d mean = Vec3d::Zero();
    Mat3d scatter = Mat3d::Zero();

    /// The centred form of `m`, whose reference point is `reference`.
    [[nodiscard]] static CentredMoments of(const Moments& m, const Vec3d& reference) {
        CentredMoments c;
        if (m.n == 0) return c;
        c.n = m.n;
        c.mean = reference + m.sum / m.n;
        c.scatter = m.sum_sq - m.sum * m.sum.transpose() / m.n;
        return c;
    }

    void merge(const CentredMoments& o) {
        if (o.n == 0) return;
        const double total = n + o.n;
        const Vec3d delta = o.mean - mean;
        scatter += o.scatter + (n * o.n / total) * delta * delta.transpose();
        mean += delta * (o.n / total);
        n = total;
    }

    /// The mean squared distance of the points to the plane with unit normal `normal` through
    /// `through`: their spread along the normal plus their centroid's offset, squared.
    [[nodiscard]] double mean_square_distance(const Vec3d& normal, const Vec3d& through) const {
        const double offset = normal.dot(mean - through);
        return normal.dot(scatter * normal) / n + offset * offset;
    }
};

}  // namespace surfgrow
