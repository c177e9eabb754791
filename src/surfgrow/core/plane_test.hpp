// The test a neighbourhood must pass to become a surface: the paper's eq. (2), or the disk test
// that also asks the points to span the ball they claim and to face the sensor.
#pragma once

#include <cmath>
#include <cstdint>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/plane_fit.hpp"

namespace surfgrow {

/// Which plane test the grower applies (docs/algorithm.md, "The plane test").
enum class PlaneTest : std::uint8_t {
    /// Eq. (2) and two more conditions: the in-plane spread must be that of a disk of the ball's
    /// radius, not of a line or a blob; and where the sensor is known, the normal must make less
    /// than the grazing limit with the line of sight (range noise spreads points along the ray,
    /// so a noise-shaped neighbourhood has its PCA normal across the ray).
    kDisk,
    kPaper,  ///< eq. (2) alone: min(lambda) < mid(lambda) / alpha
};

/// Why a neighbourhood is or is not a plane.
enum class PlaneVerdict : std::uint8_t {
    kPlane,
    kThick,    ///< fails eq. (2): an edge, a corner, clutter, or noise larger than the ball
    kNarrow,   ///< thin but not two-dimensional across the ball: a line, a blob, one spot
    kGrazing,  ///< its normal lies across the line of sight: noise along the ray, not a surface
    kKinked,   ///< thin, but its two halves lie in different planes: an edge at a small scale
};

/// Thresholds of the disk test (GrowerConfig holds the user's values).
struct DiskTest {
    double alpha = 4.0;               ///< eq. (2)
    double min_spread = 0.3;          ///< mid(lambda) >= min_spread * radius^2 / 4
    double max_incidence_deg = 85.0;  ///< normal vs line of sight, when the sensor is known
};

/// Variance along each in-plane axis of points spread evenly over a disk of radius r.
[[nodiscard]] inline double disk_variance(double radius) {
    return 0.25 * radius * radius;
}

/// The verdict on a neighbourhood of radius `radius` with ascending eigenvalues `e` and unit
/// normal `normal`. `sight` is the direction from the sensor to the home point (any length), or
/// zero when the sensor is unknown. With PlaneTest::kPaper only eq. (2) is applied.
[[nodiscard]] inline PlaneVerdict judge_plane(PlaneTest test, const DiskTest& t, const Vec3d& e,
                                              const Vec3d& normal, double radius,
                                              const Vec3d& sight) {
    if (!is_planar(e, t.alpha)) return PlaneVerdict::kThick;
    if (test == PlaneTest::kPaper) return PlaneVerdict::kPlane;
    if (e[1] < t.min_spread * disk_variance(radius)) return PlaneVerdict::kNarrow;
    const double s = sight.norm();
    if (s > 0) {
        const double cos_incidence = std::abs(normal.dot(sight)) / s;
        if (cos_incidence < std::cos(t.max_incidence_deg * (3.14159265358979323846 / 180.0)))
            return PlaneVerdict::kGrazing;
    }
    return PlaneVerdict::kPlane;
}

}  // namespace surfgrow
