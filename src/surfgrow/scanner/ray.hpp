// Rays and ray hits shared by the scanner model, the scene and the simulator.
#pragma once

#include <cstdint>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow::scanner {

/// A half line origin + t * direction, t > 0; direction is a unit vector, so t is in metres.
struct Ray {
    Vec3d origin = Vec3d::Zero();
    Vec3d direction = Vec3d::UnitX();
};

/// The nearest surface a ray meets.
struct Hit {
    double t = 0.0;                 ///< distance along the ray, metres
    std::int32_t face_id = -1;      ///< the scene's face id (see Scene::faces())
    std::int32_t primitive = -1;    ///< index of the primitive in the scene description
    Vec3d normal = Vec3d::UnitZ();  ///< unit surface normal at the hit, facing the ray origin
};

}  // namespace surfgrow::scanner
