// What the renderer draws, independent of how it was computed: disks, line segments, points.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/render/color.hpp"

namespace surfgrow::render {

/// A flat disk: a surface patch drawn as in the paper's Fig. 4c. Two-sided; shaded by `normal`.
struct Disk {
    Vec3d center = Vec3d::Zero();
    Vec3d normal = Vec3d::UnitZ();  ///< unit normal (also decides the back face when culling)
    double radius = 0.0;
    Rgb color;  ///< unshaded colour
};

/// A straight line in space (a surface normal), drawn with the renderer's line width.
struct Segment {
    Vec3d from = Vec3d::Zero();
    Vec3d to = Vec3d::Zero();
    Rgb color = kNormalRed;
    std::int32_t disk =
        -1;  ///< index of the disk it belongs to (-1: none): hidden or ghosted with it
};

/// A raw point, drawn unshaded as a small dot.
struct ScenePoint {
    Vec3f position = Vec3f::Zero();
    Rgb color = kUnassignedGrey;
    std::int32_t disk =
        -1;  ///< index of the disk it belongs to (-1: none): hidden or ghosted with it
};

/// Everything one picture shows. Coordinates are in any consistent world frame (z is up for the
/// view presets); non-finite points, and disks with a non-finite centre or a radius <= 0, draw
/// nothing.
struct Scene {
    std::vector<Disk> disks;
    std::vector<Segment> lines;
    std::vector<ScenePoint> points;
    /// One line of text under the picture, e.g. "276480 points -> 5231 surfaces, 99.4% registered".
    std::string legend;
    /// Points are depth-tested as if this much (world units) farther from the viewer, so points
    /// lying on a surface stay beneath its disk while points well in front of it still show.
    /// The surface helper sets it to the typical disk radius (mu, the registration tolerance).
    double point_depth_bias = 0.0;
};

}  // namespace surfgrow::render
