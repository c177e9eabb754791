// Per-segment least-squares planes for the tools whose segments come without one (region
// growing in PCL and CGAL returns point sets only). Counted in their algorithm time: a robot
// needs the plane, and surfgrow's output includes it.
#pragma once

#include <Eigen/Eigenvalues>
#include <cstdint>
#include <vector>

namespace peers {

/// For labels in [0, segments): the PCA plane (nx ny nz d, n.x + d = 0) of each segment's
/// points, in one pass of moments; `xyz(i)` returns point i as an Eigen::Vector3d.
template <class XYZ>
std::vector<double> fit_segment_planes(const std::vector<std::int32_t>& labels,
                                       std::size_t segments, XYZ&& xyz) {
    struct Moments {
        double n = 0;
        Eigen::Vector3d s = Eigen::Vector3d::Zero();
        Eigen::Matrix3d ss = Eigen::Matrix3d::Zero();
        Eigen::Vector3d ref = Eigen::Vector3d::Zero();  // first point: keeps the sums small
    };
    std::vector<Moments> m(segments);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (labels[i] < 0) continue;
        Moments& k = m[static_cast<std::size_t>(labels[i])];
        const Eigen::Vector3d p = xyz(i);
        if (k.n == 0) k.ref = p;
        const Eigen::Vector3d q = p - k.ref;
        k.n += 1;
        k.s += q;
        k.ss += q * q.transpose();
    }
    std::vector<double> planes(4 * segments, 0.0);
    for (std::size_t c = 0; c < segments; ++c) {
        const Moments& k = m[c];
        if (k.n < 3) continue;
        const Eigen::Vector3d mean = k.s / k.n;
        const Eigen::Matrix3d cov = k.ss / k.n - mean * mean.transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
        const Eigen::Vector3d nrm = es.eigenvectors().col(0).normalized();
        const Eigen::Vector3d centroid = mean + k.ref;
        planes[4 * c + 0] = nrm.x();
        planes[4 * c + 1] = nrm.y();
        planes[4 * c + 2] = nrm.z();
        planes[4 * c + 3] = -nrm.dot(centroid);
    }
    return planes;
}

}  // namespace peers
