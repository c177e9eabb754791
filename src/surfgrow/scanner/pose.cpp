#include "surfgrow/scanner/pose.hpp"

#include "surfgrow/scanner/noise_model.hpp"

#include <Eigen/SVD>
#include <cmath>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

namespace {

[[noreturn]] void not_rigid(std::string_view why) {
    throw Error(ErrorCode::kInvalidParameter, cat({"pose is not a rigid transform: ", why}));
}

}  // namespace

Pose rigid_from_matrix(const Eigen::Matrix4d& m, double tolerance) {
    if (!m.allFinite()) not_rigid("it has a non-finite entry");
    const Eigen::RowVector4d bottom = m.row(3);
    if ((bottom - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > tolerance)
        not_rigid(cat({"its bottom row is not 0 0 0 1 (got ", num(bottom(0)), " ", num(bottom(1)),
                       " ", num(bottom(2)), " ", num(bottom(3)), ")"}));
    const Mat3d r = m.topLeftCorner<3, 3>();
    const double ortho = (r.transpose() * r - Mat3d::Identity()).cwiseAbs().maxCoeff();
    if (ortho > tolerance)
        not_rigid(cat({"its rotation is not orthonormal (R^T R differs from I by ", num(ortho),
                       "; scale or shear?)"}));
    const double det = r.determinant();
    if (std::abs(det - 1.0) > tolerance)
        not_rigid(cat({"its rotation has determinant ", num(det), " (a reflection?)"}));
    // Nearest rotation (polar decomposition) so typing errors do not accumulate; a matrix that
    // is already orthonormal to rounding is kept bit for bit, so files round-trip exactly.
    Pose pose = Pose::Identity();
    if (ortho > 1e-12) {
        const Eigen::JacobiSVD<Mat3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
        pose.linear() = svd.matrixU() * svd.matrixV().transpose();
    } else {
        pose.linear() = r;
    }
    pose.translation() = m.topRightCorner<3, 1>();
    return pose;
}

void check_rigid(const Pose& pose, double tolerance) {
    (void)rigid_from_matrix(pose.matrix(), tolerance);
}

Mat3d rotation_from_rpy(const Vec3d& rpy_rad) {
    return (Eigen::AngleAxisd(rpy_rad.z(), Vec3d::UnitZ()) *
            Eigen::AngleAxisd(rpy_rad.y(), Vec3d::UnitY()) *
            Eigen::AngleAxisd(rpy_rad.x(), Vec3d::UnitX()))
        .toRotationMatrix();
}

Vec3d rpy_from_rotation(const Mat3d& r) {
    // atan2 rather than asin(-r20): asin loses half its digits near +-90 deg.
    const double cp = std::hypot(r(0, 0), r(1, 0));
    const double pitch = std::atan2(-r(2, 0), cp);
    if (cp < 1e-12) {
        // Gimbal lock: only yaw - roll (or yaw + roll) is defined; put it all in yaw.
        return {0.0, pitch, std::atan2(-r(0, 1), r(1, 1))};
    }
    return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
}

Pose pose_from_xyz_rpy(const Vec3d& xyz_m, const Vec3d& rpy_rad) {
    Pose pose = Pose::Identity();
    pose.linear() = rotation_from_rpy(rpy_rad);
    pose.translation() = xyz_m;
    return pose;
}

Pose perturb_pose(const Pose& pose, double sigma_m, double sigma_rad, std::uint64_t seed) {
    if (sigma_m == 0 && sigma_rad == 0) return pose;
    GaussianSource g(seed);
    const Vec3d t(g.normal() * sigma_m, g.normal() * sigma_m, g.normal() * sigma_m);
    Vec3d axis(g.normal(), g.normal(), g.normal());
    if (axis.norm() < 1e-12) axis = Vec3d::UnitZ();
    const Eigen::AngleAxisd turn(g.normal() * sigma_rad, axis.normalized());
    Pose error = Pose::Identity();
    error.linear() = turn.toRotationMatrix();
    error.translation() = t;
    return error * pose;
}

}  // namespace surfgrow::scanner
