// Parameters of surface growing, with the paper's values as defaults.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/plane_test.hpp"

namespace surfgrow {

/// The robot's workspace, the paper's answer to sparse far points: only points inside are grown.
struct WorkspaceCrop {
    std::optional<Aabb> box;       ///< keep points inside this box
    std::optional<double> radius;  ///< keep points within this distance of `center`
    std::optional<Vec3d> center;   ///< centre of the radius crop; default: the viewpoint, else 0
    [[nodiscard]] bool active() const { return box.has_value() || radius.has_value(); }
};

/// The most neighbours min_pts may ask for: more than any neighbourhood of a real scan holds.
inline constexpr int kMaxMinPts = 100000;

/// Everything surface growing needs. Lengths are in the cloud's units; the defaults assume
/// metres (the ROS / PCL / Open3D convention) and are the paper's values.
struct GrowerConfig {
    double mu =
        0.012;  ///< cube side, neighbourhood radius and default plane tolerance (paper: 12 mm)
    int min_pts = 10;  ///< fewest neighbours within mu for PCA (paper: 10); at least 3
    /// Plane test of eq. (2): accept when min(lambda) < mid(lambda) / alpha; must be > 1.
    /// The paper gives no value; 4 is measured in docs/algorithm.md: it accepts >= 99.9 % of
    /// neighbourhoods on planes at the URG-04LX's range noise and rejects those on a 90-degree
    /// edge.
    double alpha = 4.0;
    /// kDisk (default): eq. (2), and the neighbourhood must span the ball (mid(lambda) at least
    /// min_spread of a disk's r^2/4) and, where the sensor is known, face it (normal within
    /// max_incidence_deg of the line of sight); a home that fails grows its radius. kPaper: eq.
    /// (2) alone, the paper's first-come registration and a tolerance of mu per mu of radius.
    PlaneTest plane_test = PlaneTest::kDisk;
    /// Share of a disk's in-plane variance the middle eigenvalue must reach (kDisk). 0.3 passes a
    /// disk crossed by two scan lines and rejects lines and single-spot blobs (docs/algorithm.md).
    double min_spread = 0.3;
    /// Largest angle between a surface's normal and the line of sight from its home point's sensor
    /// (kDisk; when the sensor is named: scan origins or a viewpoint, not a guessed frame origin).
    /// Beyond it a "plane" is range noise along the ray.
    double max_incidence_deg = 85.0;
    /// Thickness limit in noise sigmas (kDisk): a neighbourhood whose RMS thickness
    /// sqrt(lambda_min) exceeds this many times the noise measured at its range is an edge, a
    /// step or a corner, not a plane, whatever eq. (2) says; the noise is read off the cloud
    /// itself (NoiseProfile, docs/algorithm.md).
    double thickness_sigmas = 2.5;
    /// Registration tolerance in noise sigmas (kDisk, plane_tolerance 0): a surface takes points
    /// within this many times the noise measured at its range of its plane, at least mu / 6 and
    /// at most its radius; a point already taken goes to the surface it fits best.
    double noise_sigmas = 4.0;
    /// A new surface must register at least this many points not yet registered; a home point in
    /// a small gap between earlier surfaces is left to the leftover pass instead of creating a
    /// near-duplicate surface. Raises the data reduction at equal registration.
    int min_new_points = 1;
    /// Largest distance from the fitted plane at which a point is registered, per mu of radius;
    /// 0: tied to the measured noise (kDisk, see noise_sigmas) or mu (kPaper).
    double plane_tolerance = 0.0;
    /// Adaptive radius: where a home point has fewer than min_pts neighbours within mu, or (kDisk)
    /// its neighbourhood is a line, a blob or noise rather than a plane, retry with twice the
    /// radius, then twice again, up to this multiple of mu (sparse or grazing areas, far ranges).
    /// 1 is the paper's fixed mu. The default 8 (96 mm at the paper's mu) reaches the URG-04LX's
    /// 4 m, where points lie 25 mm apart with 8 mm of noise (docs/algorithm.md).
    double adaptive_factor = 8.0;
    /// Attach each point left unregistered by growing to the neighbouring surface whose plane it
    /// fits best, if within the plane tolerance. Closes the gap at edges and in sparse areas.
    /// With kDisk, then grow strips from what is still left: faces narrower than any ball around
    /// them, such as a flange's edge (the strip test, docs/algorithm.md); not in fused clouds.
    bool attach_leftovers = true;
    /// Normal refinement: each surface's normal is refitted over its own neighbourhood and those of
    /// adjacent surfaces in the same plane (normals within this angle, centroids on each other's
    /// plane within 3 noise sigmas). Halves the normal noise of mu-sized patches without crossing
    /// edges. 0 turns it off (the paper's per-patch normals).
    double pool_angle_deg = 15.0;
    double pool_radius = 0.0;  ///< home points within this distance are candidates; 0 means 4 mu
    std::uint64_t seed = 1;    ///< home points are drawn from this seed; same seed, same result
    int threads = 0;           ///< worker threads; 0 = all cores. Results do not depend on it
    WorkspaceCrop crop;
    /// Sensor origin for orienting normals and measuring range; overrides the cloud's own.
    std::optional<Vec3d> viewpoint;
    double range_band = 1.0;  ///< width of the range bands in the statistics
    /// Called with a stage name and the fraction done, from one thread at a time. May be empty.
    /// It may throw to stop the run: the grower stops after the slabs in flight and throws it on.
    std::function<void(std::string_view stage, double fraction)> progress;

    /// The fixed tolerance per mu of radius: plane_tolerance, or mu; 0 when tied to the noise.
    [[nodiscard]] double tolerance() const {
        if (plane_tolerance > 0) return plane_tolerance;
        return plane_test == PlaneTest::kPaper ? mu : 0.0;
    }
    [[nodiscard]] DiskTest disk_test() const { return {alpha, min_spread, max_incidence_deg}; }
    [[nodiscard]] double max_radius() const { return adaptive_factor * mu; }
    /// The pooling radius with its default resolved (4 mu: docs/algorithm.md).
    [[nodiscard]] double pooling_radius() const { return pool_radius > 0 ? pool_radius : 4 * mu; }
};

/// Throws Error(kInvalidParameter) naming the first parameter out of range.
void validate(const GrowerConfig& config);

}  // namespace surfgrow
