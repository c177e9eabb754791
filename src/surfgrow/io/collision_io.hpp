// collision_spheres.json and .ply (the environment for other tools) and the collision report.
#pragma once

#include <ostream>
#include <span>
#include <string>

#include "surfgrow/io/results_io.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/robot_model.hpp"

namespace surfgrow::io {

/// Where collision_spheres.json (version 2) says its spheres are, beside it.
inline constexpr const char* kCollisionSpheresFile = "collision_spheres.ply";

/// collision_spheres.json (version 2): units, count and radius range of the environment's
/// spheres; the spheres themselves are in collision_spheres.ply ("spheres_file"). Deterministic.
void write_collision_spheres_json(std::ostream& out, const CollisionSpheres& spheres,
                                  const ResultMeta& meta);

/// collision_spheres.ply: one vertex per sphere, sphere id = surface id order, binary
/// little-endian: x, y, z (the centre, file coordinates), radius. Float, positions in double when
/// meta.offset is non-zero (georeferenced); result_id in a comment.
void write_collision_spheres_ply(std::ostream& out, const CollisionSpheres& spheres,
                                 const ResultMeta& meta);

/// What a collision check was asked.
struct CollisionRequest {
    std::string robot;       ///< the robot file's name, for the record
    double tolerance = 0.0;  ///< safety margin, in the result's units
};

/// collision.json: per link its type, clearance, whether it collides, and the nearest surface
/// (id, home point, radius); overall the smallest clearance and the colliding link count.
/// Clearances of an empty environment are null. Deterministic.
void write_collision_report_json(std::ostream& out, const CollisionSpheres& spheres,
                                 const RobotModel& robot, std::span<const LinkClearance> results,
                                 const CollisionRequest& request, const ResultMeta& meta);

}  // namespace surfgrow::io
