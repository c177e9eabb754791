// A close view of one corner of a structure, as in the paper's Fig. 6 (d)-(f).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/render/scene.hpp"

namespace surfgrow::render {

/// Where a close-up looks. The picture shows the square of side 2 * half_size around `center`,
/// seen along `forward`, and only the disks (with their points and normals) within
/// kCloseUpReach * half_size of the centre, so nothing between the camera and the corner hides
/// it.
struct CloseUp {
    Vec3d center = Vec3d::Zero();
    Vec3d forward = Vec3d(-1, 1, -1).normalized();  ///< unit: the direction the camera looks
    double half_size = 1.0;                         ///< world units, > 0
};

inline constexpr double kCloseUpReach = 1.5;

/// The side of a corner close-up in median disk radii: about twelve disks across each face.
inline constexpr double kCloseUpRadii = 12.0;

/// The corner of a structure where three groups of disks (`groups[i]` for disks[i], e.g. bound
/// planes; -1 none) of clearly different orientation (more than 40 degrees apart) meet, as many
/// disks of each of the three within the close-up as possible; among the twelve largest groups.
/// Looked at against the mean of their normals (which face the sensor), so every face shows its
/// front. Where no three groups meet, the same for two (an edge). nullopt when no two groups
/// meet, or `groups` is not one per disk.
[[nodiscard]] std::optional<CloseUp> find_corner(std::span<const Disk> disks,
                                                 std::span<const std::int32_t> groups);

}  // namespace surfgrow::render
