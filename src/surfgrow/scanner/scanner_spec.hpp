// Everything that defines a tilting-laser scan: laser, servo, mounting offset, readings per ray.
#pragma once

#include <cstddef>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/scanner/laser_spec.hpp"
#include "surfgrow/scanner/tilt_spec.hpp"

namespace surfgrow::scanner {

/// A scan is tilt.positions x laser.steps() rays with readings_per_ray readings each (the paper's
/// n, eq. 1). Defaults are the paper's set-up; the offset and n are not given in the paper.
struct ScannerSpec {
    LaserSpec laser = {};
    TiltSpec tilt = {};
    /// Laser optical centre relative to the sensor origin (a point on the tilt axis), in the laser
    /// frame, metres. Default: 40 mm above the axis, an assumed bracket height (the paper gives
    /// none; the URG-04LX's window is about that high above its base).
    Vec3d optical_offset_m = Vec3d(0.0, 0.0, 0.040);
    int readings_per_ray = 5;  ///< n: readings taken at each (tilt, step), 1..255

    [[nodiscard]] std::size_t rays() const {
        return static_cast<std::size_t>(tilt.positions) * static_cast<std::size_t>(laser.steps());
    }
    [[nodiscard]] std::size_t readings() const {
        return rays() * static_cast<std::size_t>(readings_per_ray);
    }

    /// Validates laser and tilt, the offset (finite, under 1 m) and n; also bounds the total
    /// readings (at most 2^28) so no spec can ask for an absurd allocation.
    /// Throws Error(kInvalidParameter).
    void validate() const;

    friend bool operator==(const ScannerSpec&, const ScannerSpec&) = default;
};

/// Most readings one scan may hold (2^28: 512 MiB of uint16).
inline constexpr std::size_t kMaxReadingsPerScan = std::size_t{1} << 28;

}  // namespace surfgrow::scanner
