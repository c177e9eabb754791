#include "surfgrow/robot/robot_model.hpp"

#include <cmath>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

std::vector<LinkClearance> check_robot(const CollisionSpheres& environment, const RobotModel& robot,
                                       double tolerance) {
    if (!std::isfinite(tolerance))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"collision tolerance must be finite, got ", num(tolerance)}));
    std::vector<LinkClearance> out(robot.links.size());
    for (std::size_t i = 0; i < robot.links.size(); ++i) {
        const RobotLink& link = robot.links[i];
        if (!is_valid(link.shape))
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"robot link '", link.name,
                             "' needs finite coordinates and a finite radius >= 0"}));
        out[i].proximity = environment.nearest(link.shape);
        out[i].collides = out[i].proximity.clearance < tolerance;
    }
    return out;
}

const char* link_kind_name(RobotLink::Kind kind) {
    return kind == RobotLink::Kind::kCapsule ? "capsule" : "sphere";
}

}  // namespace surfgrow
