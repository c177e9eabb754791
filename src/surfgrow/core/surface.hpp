// A surface patch: the unit of output of surface growing (paper section 4.2).
#pragma once

#include <cstdint>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// One grown surface: a plane fitted to the points around a home point, and the points it took.
/// All positions are in the cloud's units and frame (relative to PointCloud::offset).
struct Surface {
    Vec3d home = Vec3d::Zero();         ///< the home point it grew from
    Vec3d normal = Vec3d::UnitZ();      ///< unit normal, oriented towards the sensor side
    Vec3d centroid = Vec3d::Zero();     ///< centroid of the neighbourhood; the plane passes here
    Vec3d eigenvalues = Vec3d::Zero();  ///< covariance eigenvalues, ascending [units^2]
    double radius = 0.0;                ///< neighbourhood radius used (mu, or larger if adapted)
    std::uint32_t neighbours = 0;       ///< points within `radius` of the home point (PCA support)
    std::uint32_t point_count = 0;      ///< member points (registered to this surface)
    double mean_residual = 0.0;         ///< mean |distance| of members to the plane
    double tolerance = 0.0;             ///< largest distance from the plane of a member
    Aabb bounds;                        ///< bounding box of the members

    /// Plane offset d in n.x + d = 0.
    [[nodiscard]] double plane_offset() const { return -normal.dot(centroid); }
    [[nodiscard]] Plane plane() const { return Plane::through(centroid, normal); }
};

}  // namespace surfgrow
