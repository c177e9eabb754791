// Bound planes (paper sections 4.2 and 6): adjacent coplanar patches merged into planar regions,
// each with its plane, members, area and boundary polygon.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/surface.hpp"
#include "surfgrow/planes/polygon2d.hpp"

namespace surfgrow {

struct BoundPlaneMemo;  // bound_plane_memo.hpp

/// Parameters of region merging and boundary tracing. Lengths are in the cloud's units; a length
/// of 0 means the default derived from `mu` (resolved values are in BoundPlanes::config).
struct BoundPlaneConfig {
    double mu = 0.012;  ///< the radius the surfaces were grown with (GrowerConfig::mu)
    /// Merge a patch when its normal is within this angle of its neighbour's and of the region's
    /// running plane (unoriented).
    double max_angle_deg = 10.0;
    /// ... and its centroid within this distance of the neighbour's plane (and the neighbour's of
    /// its), and of the region's plane. 0: 3 x the measured noise (median of the patches' RMS
    /// thickness sqrt(lambda_min)), clamped to [mu / 4, mu / 2].
    double max_offset = 0.0;
    /// Two patches are neighbours when member points of each lie within this distance (0: mu / 2),
    /// or their home points within the sum of their radii.
    double adjacency = 0.0;
    /// Coplanar regions whose patches come within this distance of each other are one face
    /// (occlusion shadows, sparse bands); 0: 5 mu; negative: never bridge gaps.
    double max_gap = 0.0;
    double resolution = 0.0;  ///< boundary raster cell (0: mu / 2)
    /// Gaps narrower than about twice this are closed in the boundary (0: the larger of the
    /// resolution and 1.5 x the region's point spacing, measured from its patches).
    double closing_radius = 0.0;
    double simplify_tolerance = 0.0;  ///< Douglas-Peucker tolerance of the polygons (0: resolution)
    int threads = 0;                  ///< 0 = all cores; the result does not depend on it
};

/// The largest adjacency distance, in mu: beyond it every point is paired with thousands.
inline constexpr double kMaxAdjacencyPerMu = 4.0;

/// Throws Error(kInvalidParameter) naming the first parameter out of range: every length within
/// float coordinates' range (length_limits.hpp), the adjacency at most kMaxAdjacencyPerMu mu.
void validate(const BoundPlaneConfig& config);

/// One planar region: a structural face (a flange, a web, the deck).
struct BoundPlane {
    Vec3d normal = Vec3d::UnitZ();       ///< unit, facing the sensor (majority of its patches)
    Vec3d centroid = Vec3d::Zero();      ///< of the inlier member points; the plane passes here
    Vec3d u_axis = Vec3d::UnitX();       ///< in-plane principal axis (largest spread)
    Vec3d v_axis = Vec3d::UnitY();       ///< normal x u_axis
    double area = 0.0;                   ///< of the polygons, holes subtracted [units^2]
    double rms = 0.0;                    ///< RMS distance of the member points to the plane
    double closing_radius = 0.0;         ///< the gap closing used for this region's boundary
    std::uint64_t point_count = 0;       ///< member points
    std::vector<std::uint32_t> patches;  ///< member surface ids, ascending
    Aabb bounds;                         ///< of the member points
    /// The member points define no plane: collinear (or fewer than 3), or their plane lies more
    /// than 45 degrees from the mean normal of their patches that span their balls (a strip
    /// narrower than its noise along its normal). The normal is then the patches' mean and the
    /// polygon a thin strip.
    bool degenerate = false;
    /// Boundary in plane coordinates (a, b): the point centroid + a u_axis + b v_axis.
    std::vector<PolygonWithHoles> polygons;

    [[nodiscard]] Plane plane() const { return Plane::through(centroid, normal); }
    [[nodiscard]] Vec3d to_world(const Vec2d& q) const {
        return centroid + q.x() * u_axis + q.y() * v_axis;
    }
    [[nodiscard]] Vec2d to_plane(const Vec3d& p) const {
        return {(p - centroid).dot(u_axis), (p - centroid).dot(v_axis)};
    }
};

struct BoundPlaneStats {
    std::uint64_t patches = 0;         ///< surfaces in the result
    std::uint64_t patches_merged = 0;  ///< surfaces in some plane (those with member points)
    std::uint64_t adjacent_pairs = 0;  ///< patch adjacency graph edges
    std::uint64_t points = 0;          ///< member points of all planes
    std::uint64_t degenerate = 0;      ///< planes whose points define none (BoundPlane)
    double area = 0.0;                 ///< sum of the planes' areas
    double noise = 0.0;                ///< median patch thickness sqrt(lambda_min)
};

struct BoundPlanes {
    /// Ordered by point count (descending), then by smallest member patch id.
    std::vector<BoundPlane> planes;
    /// For every surface, the plane it belongs to, or -1 (no member points).
    std::vector<std::int32_t> plane_of_patch;
    BoundPlaneConfig config;  ///< the parameters used, every default resolved
    BoundPlaneStats stats;
};

/// Merges the surfaces of a grow result into bound planes.
///
/// Patches are the graph's nodes, adjacency its edges. Regions grow breadth-first from seeds
/// taken in order of decreasing member count; a neighbour joins when it is coplanar with the
/// patch it is reached from and with the region's plane as refitted so far on all its member
/// points (pooled moments), so a gently curving surface cannot drift into one region. Each region's
/// plane is then fitted to all its member points; its boundary is traced on a raster of them
/// (rasterise_points, trace_boundaries). Deterministic, the same for any thread count.
///
/// `labels[i]` is the surface of cloud point i or -1 (GrowResult::labels). Throws
/// Error(kInvalidParameter) when the labels do not match the cloud or the surfaces, a surface has
/// a non-unit normal, or the configuration is out of range. An empty result gives no planes.
///
/// With a `memo` (bound_plane_memo.hpp), what it holds from the last call is reused where the
/// patches only gained members since (a map: pipeline/map.hpp), and it is refreshed: the same
/// regions, and the same plane of each (normal, centroid, RMS, box), in less time; a region that
/// changed has its boundary traced on the cell counts the memo kept, within a raster cell of the
/// one traced anew (detail::extend_region). A memo that does not fit the patches is ignored.
[[nodiscard]] BoundPlanes compute_bound_planes(const CloudView& cloud,
                                               std::span<const Surface> surfaces,
                                               std::span<const std::int32_t> labels,
                                               const BoundPlaneConfig& config,
                                               BoundPlaneMemo* memo = nullptr);

/// The same from a GrowResult (its surfaces and labels): what `surfgrow grow` calls.
[[nodiscard]] inline BoundPlanes compute_bound_planes(const CloudView& cloud,
                                                      const GrowResult& result,
                                                      const BoundPlaneConfig& config) {
    return compute_bound_planes(cloud, result.surfaces, result.labels, config);
}

/// The plane of every point: plane_of_patch of its surface label, or -1.
[[nodiscard]] std::vector<std::int32_t> plane_labels(const BoundPlanes& planes,
                                                     std::span<const std::int32_t> labels);

}  // namespace surfgrow
