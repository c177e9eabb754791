// How the laser sits on the tilt servo, estimated from scans of one large flat surface: the
// optical centre's height above the tilt axis (a wrong one bends every plane with the tilt) and
// the servo's zero (a turned horn tilts the whole scan; seen only between scans from different
// poses). docs/scanner.md, "Calibration".
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/scanner/raw_scan.hpp"

namespace surfgrow::scanner {

/// The mounting a scan is converted with.
struct Calibration {
    double optical_offset_m = 0.040;  ///< optical centre above the tilt axis (laser frame z)
    double tilt_zero_deg = 0.0;       ///< the laser's tilt when the servo reads 0
};

struct CalibrationOptions {
    int trim_q = 1;                  ///< q of eq. (1) for the ranges used
    double inlier_m = 0.03;          ///< first choice of the surface's points: within this of it
    std::size_t max_points = 20000;  ///< points used at most (an even spread of the surface's)
    std::uint64_t seed = 1;          ///< for the search of the largest plane
    /// Sigma of each scan's range scale error, a share of the range that repeated readings do
    /// not average away (colour, material, drift). URG-04LX: its datasheet's 1 % at 2 sigma,
    /// half of it systematic (NoiseModel): 0.5 % x sqrt(0.5). Part of the reported sigmas.
    double range_scale_sigma = 0.0035;
    /// An offset known to worse than this is refused (an error, not a result): the surface
    /// does not bend with it, e.g. a wall seen edge-on or over a few tilt rows.
    double max_offset_sigma_m = 0.005;
    /// A surface whose points, once calibrated, still bow away from their plane by more than
    /// this (RMS of the best quadric through their distances) is refused: it is not flat (a
    /// tank wall, a hull), and the offset would have been bent to flatten it. A flat floor
    /// leaves well under a millimetre.
    double max_bow_m = 0.002;
};

struct CalibrationResult {
    Calibration calibration;
    /// Standard errors: the residuals' scatter and the sensor's systematic range error
    /// (CalibrationOptions::range_scale_sigma) propagated.
    double offset_sigma_m = 0.0;
    /// False with one scan, or when the scans' poses cannot tell the zero (they differ only
    /// along the surface): the zero is then the scans' own (0) and its sigma 0.
    bool zero_estimated = false;
    double zero_sigma_deg = 0.0;
    Plane plane;                ///< the surface, world frame
    std::size_t points = 0;     ///< points of the surface used
    double rms_before_m = 0.0;  ///< their distance to it as the scans were recorded
    double rms_after_m = 0.0;   ///< and with the estimate
    double bow_m = 0.0;         ///< RMS of the smooth shape left in them (see max_bow_m)
};

/// Estimates the mounting from scans in which one flat surface (a wall, a floor, a steel plate:
/// the larger the better, seen over as many tilt positions as possible) is the largest plane.
/// With several scans, their poses must be right and the same surface must be in each; the zero
/// is estimated when the poses differ across the surface (e.g. a floor scanned from two places
/// along it). Deterministic for a given seed. Throws Error(kInvalidParameter) for no scans,
/// invalid ones, too few points on a plane (under 500), partial scans, a plane that cannot
/// tell the offset (its sigma above options.max_offset_sigma_m) or one that is not flat (its
/// bow above options.max_bow_m).
[[nodiscard]] CalibrationResult calibrate(std::span<const RawScan> scans,
                                          const CalibrationOptions& options = {});

/// The scan as if it had been recorded with `c`: its optical offset's z replaced, `c`'s zero
/// added to every tilt angle (the read-back ones, or the plan's).
void apply_calibration(RawScan& scan, const Calibration& c);

}  // namespace surfgrow::scanner
