// collision_spheres.json (the environment for other tools) and the collision report.
#pragma once

#include <ostream>
#include <span>
#include <string>

#include "surfgrow/io/results_io.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/robot_model.hpp"

namespace surfgrow::io {

/// collision_spheres.json: every environment sphere as [x, y, z, radius] (file coordinates), in
/// sphere id = surface id order, with units and the radius range. Deterministic.
void write_collision_spheres_json(std::ostream& out, const CollisionSpheres& spheres,
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
