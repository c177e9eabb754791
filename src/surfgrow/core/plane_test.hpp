// The test a neighbourhood must pass to become a surface: the paper's eq. (2), or the disk test
// that also asks the points to span the ball they claim and to face the sensor; and the strip test
// for the faces narrower than a ball, among the points no surface took.
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

/// Whether a plane with unit `normal` is seen edge-on: its normal makes more than
/// `max_incidence_deg` with `sight`, the direction from the sensor (any length; zero: unknown,
/// never edge-on).
[[nodiscard]] inline bool edge_on(const Vec3d& normal, const Vec3d& sight,
                                  double max_incidence_deg) {
    const double s = sight.norm();
    return s > 0 && std::abs(normal.dot(sight)) / s <
                        std::cos(max_incidence_deg * (3.14159265358979323846 / 180.0));
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
    if (edge_on(normal, sight, t.max_incidence_deg)) return PlaneVerdict::kGrazing;
    return PlaneVerdict::kPlane;
}

/// Thresholds of the strip test (docs/algorithm.md, "Strips"): a face narrower than any ball
/// around it (a flange's edge, a plate's end), judged on the points no surface took.
struct StripTest {
    double min_width_sigmas = 3.0;  ///< RMS width sqrt(mid(lambda)) >= this many noise sigmas
    double max_tilt_deg = 4.0;      ///< standard error of the normal across the strip's axis
    double min_line_ratio = 0.05;   ///< mid(lambda) >= this * max(lambda): not a line
    double min_blob_ratio = 0.05;   ///< max(lambda) >= this * radius^2: not one spot
};

/// The verdict on a strip candidate of `count` points in a ball of radius `radius`, ascending
/// eigenvalues `e`, unit normal `normal`, at a range where the measured noise is `sigma` and a
/// plane may be at most `max_var` thick (variance); `sight` as for judge_plane. A strip need not
/// span the ball, only be two-dimensional beyond doubt: wider than the noise by min_width_sigmas,
/// and with enough points that its normal tilts by at most max_tilt_deg about its long axis
/// (sigma / sqrt(count * mid(lambda)) radians).
[[nodiscard]] inline PlaneVerdict judge_strip(const DiskTest& t, const StripTest& strip,
                                              const Vec3d& e, double count, const Vec3d& normal,
                                              double radius, double sigma, double max_var,
                                              const Vec3d& sight) {
    if (!is_planar(e, t.alpha) || e[0] > max_var) return PlaneVerdict::kThick;
    const double width = strip.min_width_sigmas * sigma;
    if (e[1] < width * width || e[1] < strip.min_line_ratio * e[2] ||
        e[2] < strip.min_blob_ratio * radius * radius)
        return PlaneVerdict::kNarrow;
    if (sigma > strip.max_tilt_deg * (3.14159265358979323846 / 180.0) * std::sqrt(count * e[1]))
        return PlaneVerdict::kNarrow;
    if (edge_on(normal, sight, t.max_incidence_deg)) return PlaneVerdict::kGrazing;
    return PlaneVerdict::kPlane;
}

}  // namespace surfgrow
