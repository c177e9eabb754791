// robot.json: a robot's collision model as named spheres and capsules
// (docs/occupancy-and-collision.md).
#pragma once

#include <filesystem>
#include <string_view>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/robot/robot_model.hpp"

namespace surfgrow::io {

/// Where robot.json's coordinates go: lengths are converted from the file's "units" to
/// `metres_per_unit` (the result's unit), then `offset` is subtracted (file coordinates to the
/// cloud's frame, as for surfaces).
struct RobotFrame {
    double metres_per_unit = 1.0;
    Vec3d offset = Vec3d::Zero();
};

/// Parses robot.json held in memory; `source` names it in messages.
///
/// {"units": "m", "links": [
///    {"name": "base", "type": "sphere", "centre": [0, 0, 0.2], "radius": 0.15},
///    {"name": "arm", "type": "capsule", "a": [0, 0, 0.3], "b": [0.4, 0, 0.3], "radius": 0.06}]}
///
/// "units" is m, cm or mm and required; "format", if present, must be "surfgrow-robot". "center"
/// may stand for "centre". A capsule with a == b is accepted and is a sphere. Throws
/// Error(kMalformedInput) naming the source and the link for: invalid JSON, a missing or unknown
/// field, an unknown type, a vector that is not three finite numbers, a radius that is not a
/// finite number > 0, an empty or duplicate name, no links.
[[nodiscard]] RobotModel parse_robot_json(std::string_view text, std::string_view source,
                                          const RobotFrame& frame);

/// Reads robot.json. Throws Error(kCannotOpen) if it cannot be read, else as parse_robot_json().
[[nodiscard]] RobotModel read_robot_json(const std::filesystem::path& file,
                                         const RobotFrame& frame);

}  // namespace surfgrow::io
