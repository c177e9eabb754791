// A robot as collision shapes: named links, each a sphere or a capsule (paper section 5.5).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "surfgrow/robot/collision_shapes.hpp"
#include "surfgrow/robot/collision_spheres.hpp"

namespace surfgrow {

/// One link of the robot's collision model. A sphere is stored as a capsule with a == b.
struct RobotLink {
    enum class Kind : std::uint8_t { kSphere, kCapsule };
    std::string name;
    Kind kind = Kind::kSphere;
    Capsule shape;
};

/// The robot in one pose: its links, in the environment's frame and units.
struct RobotModel {
    std::vector<RobotLink> links;
};

/// What one link sees.
struct LinkClearance {
    Proximity proximity;    ///< clearance to and id of the nearest environment sphere
    bool collides = false;  ///< proximity.clearance < tolerance
};

/// The clearance of every link (same order as robot.links) with `tolerance` as the safety margin.
/// Throws Error(kInvalidParameter) for a link with a bad shape or a non-finite tolerance.
[[nodiscard]] std::vector<LinkClearance> check_robot(const CollisionSpheres& environment,
                                                     const RobotModel& robot, double tolerance);

/// The kind's name in robot files and reports: "sphere" or "capsule".
[[nodiscard]] const char* link_kind_name(RobotLink::Kind kind);

}  // namespace surfgrow
