// Parameters of surface growing, with the paper's values as defaults.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// The robot's workspace, the paper's answer to sparse far points: only points inside are grown.
struct WorkspaceCrop {
    std::optional<Aabb> box;       ///< keep points inside this box
    std::optional<double> radius;  ///< keep points within this distance of `center`
    std::optional<Vec3d> center;   ///< centre of the radius crop; default: the viewpoint, else 0
    [[nodiscard]] bool active() const { return box.has_value() || radius.has_value(); }
};

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
    /// A new surface must register at least this many points not yet registered; a home point in
    /// a small gap between earlier surfaces is left to the leftover pass instead of creating a
    /// near-duplicate surface. Raises the data reduction at equal registration.
    int min_new_points = 1;
    /// Largest distance from the fitted plane at which a point is registered; 0 means mu (paper).
    double plane_tolerance = 0.0;
    /// Adaptive radius: where a home point has fewer than min_pts neighbours within mu, retry with
    /// twice the radius, then twice again, up to this multiple of mu (sparse or grazing areas,
    /// far ranges); the plane tolerance scales with the radius. 1 is the paper's fixed mu. The
    /// default 2 registers ~100 % instead of ~87 % of a single I-beam scan within 1.5 m, for
    /// +0.2 degree of p95 normal error (docs/algorithm.md).
    double adaptive_factor = 2.0;
    /// Attach each point left unregistered by growing to the neighbouring surface whose plane it
    /// fits best, if within the plane tolerance. Closes the gap at edges and in sparse areas.
    bool attach_leftovers = true;
    /// Normal refinement: each surface's normal is refitted over its own neighbourhood and those of
    /// adjacent surfaces in the same plane (normals within this angle, centroids on each other's
    /// plane within 3 noise sigmas). Halves the normal noise of mu-sized patches without crossing
    /// edges. 0 turns it off (the paper's per-patch normals).
    double pool_angle_deg = 15.0;
    double pool_radius = 0.0;  ///< home points within this distance are candidates; 0 means 2 mu
    std::uint64_t seed = 1;    ///< home points are drawn from this seed; same seed, same result
    int threads = 0;           ///< worker threads; 0 = all cores. Results do not depend on it
    WorkspaceCrop crop;
    /// Sensor origin for orienting normals and measuring range; overrides the cloud's own.
    std::optional<Vec3d> viewpoint;
    double range_band = 1.0;  ///< width of the range bands in the statistics
    /// Called with a stage name and the fraction done, from one thread at a time. May be empty.
    std::function<void(std::string_view stage, double fraction)> progress;

    [[nodiscard]] double tolerance() const { return plane_tolerance > 0 ? plane_tolerance : mu; }
    [[nodiscard]] double max_radius() const { return adaptive_factor * mu; }
};

/// Throws Error(kInvalidParameter) naming the first parameter out of range.
void validate(const GrowerConfig& config);

}  // namespace surfgrow
