// Rigid poses: validation of 4x4 matrices and the x,y,z,roll,pitch,yaw convention.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow::scanner {

/// A scanner pose maps sensor-frame points to the world: p_world = pose * p_sensor.
using Pose = Eigen::Isometry3d;

/// Largest element of |R^T R - I|, |det R - 1| and of the bottom row's deviation from 0 0 0 1
/// accepted for a rigid transform. Loose enough for matrices typed with 4-5 digits, tight enough
/// to reject any scale or shear that matters (a 1.001 scale is 2e-3 off).
inline constexpr double kRigidTolerance = 1e-4;

/// The rigid transform held by `m` (row-major as written: m(row, col)), with its rotation
/// re-orthonormalised so later maths sees an exact rotation. Throws Error(kInvalidParameter)
/// naming the defect if `m` is not finite, its bottom row is not 0 0 0 1, its rotation is not
/// orthonormal, or it is a reflection (det -1).
[[nodiscard]] Pose rigid_from_matrix(const Eigen::Matrix4d& m, double tolerance = kRigidTolerance);

/// Throws Error(kInvalidParameter) unless `pose`'s matrix is rigid (see rigid_from_matrix).
void check_rigid(const Pose& pose, double tolerance = kRigidTolerance);

/// Rotation from roll, pitch, yaw in radians: R = Rz(yaw) * Ry(pitch) * Rx(roll), i.e. roll about
/// the fixed x axis first, then pitch about fixed y, then yaw about fixed z (ROS / URDF rpy).
[[nodiscard]] Mat3d rotation_from_rpy(const Vec3d& rpy_rad);

/// Inverse of rotation_from_rpy with pitch in [-pi/2, pi/2]; at pitch = +-pi/2 (gimbal lock)
/// roll is set to 0 and the whole rotation about z goes into yaw.
[[nodiscard]] Vec3d rpy_from_rotation(const Mat3d& rotation);

/// Pose from a position in metres and roll, pitch, yaw in radians (see rotation_from_rpy).
[[nodiscard]] Pose pose_from_xyz_rpy(const Vec3d& xyz_m, const Vec3d& rpy_rad);

/// `pose` moved by a small random rigid error, as a robot's pose estimate errs: a translation with
/// each axis drawn from N(0, sigma_m) and a rotation about a random axis by an angle drawn from
/// N(0, sigma_rad), both from `seed` alone. Multi-pose fusion with such recorded poses stacks a
/// surface in slightly shifted layers, as real fused scans do. Zero sigmas return `pose`.
[[nodiscard]] Pose perturb_pose(const Pose& pose, double sigma_m, double sigma_rad,
                                std::uint64_t seed);

[[nodiscard]] inline double deg_to_rad(double deg) {
    return deg * (3.14159265358979323846 / 180.0);
}
[[nodiscard]] inline double rad_to_deg(double rad) {
    return rad * (180.0 / 3.14159265358979323846);
}

}  // namespace surfgrow::scanner
