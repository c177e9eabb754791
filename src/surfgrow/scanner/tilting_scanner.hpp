// The paper's 3D scanning tool: a 2D laser on a tilt servo (section 3, Fig. 1c and 2).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/scanner/pose.hpp"
#include "surfgrow/scanner/ray.hpp"
#include "surfgrow/scanner/scanner_spec.hpp"

namespace surfgrow::scanner {

/// Geometry of a tilting 2D laser scanner.
///
/// Frames (all right-handed, metres):
///  - sensor frame S: origin on the tilt axis, x forward, y left, z up; the tilt axis is S's y
///  axis.
///    A scan's pose maps S to the world.
///  - laser frame L(tilt): S rotated about y so that a positive tilt raises the forward axis
///    (L = Ry(-tilt) in S: x_L = (cos tilt, 0, sin tilt)). The laser's optical centre sits at
///    optical_offset_m in L, so it swings around the axis as the servo tilts.
///  - the beam at pan angle p leaves the optical centre along (cos p, sin p, 0) in L: the scan
///    plane is L's x-y plane and pan turns about L's z axis, counter-clockwise seen from +z.
///
/// A reading r (metres) along the ray of (tilt index i, step index j) is the sensor-frame point
/// R_i * (offset + r * (cos p_j, sin p_j, 0)). Step index j counts from 0 and means the device
/// step laser.first_step + j; tilt index i means tilt.first_deg + i * tilt.step_deg.
class TiltingScanner {
  public:
    /// Throws Error(kInvalidParameter) if the spec is invalid.
    explicit TiltingScanner(ScannerSpec spec = {});
    /// Tilt position i at `tilt_deg[i]` (the servo's read-back angles) instead of the spec's
    /// planned angle; an empty span means the plan. Throws Error(kInvalidParameter) if the spec
    /// is invalid or the angles are not one per position.
    TiltingScanner(ScannerSpec spec, std::span<const double> tilt_deg);

    [[nodiscard]] const ScannerSpec& spec() const { return spec_; }
    [[nodiscard]] int tilt_count() const { return spec_.tilt.positions; }
    [[nodiscard]] int step_count() const { return spec_.laser.steps(); }
    [[nodiscard]] std::size_t ray_count() const { return spec_.rays(); }
    /// Rays are numbered tilt-major: index = tilt * step_count() + step.
    [[nodiscard]] std::size_t ray_index(int tilt, int step) const {
        return static_cast<std::size_t>(tilt) * static_cast<std::size_t>(step_count()) +
               static_cast<std::size_t>(step);
    }

    [[nodiscard]] double tilt_rad(int tilt) const;
    [[nodiscard]] double pan_rad(int step) const;
    [[nodiscard]] bool can_detect(int step) const { return spec_.laser.can_detect(step); }

    /// Rotation of the laser frame into the sensor frame at a tilt position.
    [[nodiscard]] const Mat3d& tilt_rotation(int tilt) const { return tilt_rot_[tilt]; }
    /// Optical centre in the sensor frame at a tilt position.
    [[nodiscard]] Vec3d optical_centre(int tilt) const;
    /// Unit beam direction in the laser frame (z = 0) for a step.
    [[nodiscard]] Vec3d beam_in_laser(int step) const {
        return {pan_cos_[step], pan_sin_[step], 0.0};
    }

    /// The beam of (tilt, step) in the sensor frame: origin at the optical centre.
    [[nodiscard]] Ray ray(int tilt, int step) const;
    /// The sensor-frame point at `range_m` along the beam of (tilt, step).
    [[nodiscard]] Vec3d to_sensor(int tilt, int step, double range_m) const;
    /// The world point at `range_m` along the beam of (tilt, step) for a scan taken at `pose`.
    [[nodiscard]] Vec3d to_world(const Pose& pose, int tilt, int step, double range_m) const {
        return pose * to_sensor(tilt, step, range_m);
    }

  private:
    ScannerSpec spec_;
    std::vector<double> tilt_deg_;
    std::vector<Mat3d> tilt_rot_;
    std::vector<double> pan_cos_;
    std::vector<double> pan_sin_;
};

}  // namespace surfgrow::scanner
