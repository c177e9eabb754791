#include "surfgrow/io/collision_io.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "surfgrow/io/output_buffer.hpp"

namespace surfgrow::io {

namespace {

using Json = nlohmann::ordered_json;

Json vec_json(const Vec3d& v) {
    return Json::array({v.x(), v.y(), v.z()});
}

Json length_or_null(double v) {
    return std::isfinite(v) ? Json(v) : Json(nullptr);
}

}  // namespace

void write_collision_spheres_json(std::ostream& out, const CollisionSpheres& spheres,
                                  const ResultMeta& meta) {
    double rmin = 0, rmax = 0;
    if (!spheres.empty()) {
        rmin = rmax = spheres.spheres().front().radius;
        for (const Sphere& s : spheres.spheres()) {
            rmin = std::min(rmin, s.radius);
            rmax = std::max(rmax, s.radius);
        }
    }
    const Json head = {
        {"format", "surfgrow-collision-spheres"},
        {"version", 1},
        {"units", meta.units},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"what",
         "one sphere per surface: centre at its home point, radius its neighbourhood "
         "radius (paper 5.5); id = surface id; rows are [x, y, z, radius]"},
        {"count", spheres.size()},
        {"radius", {{"min", rmin}, {"max", rmax}}},
    };
    std::string text = head.dump(1);
    text.pop_back();  // the closing brace: the spheres go in before it
    while (!text.empty() && text.back() == '\n') text.pop_back();
    OutputBuffer buf(out);
    buf.append(text);
    buf.append(",\n \"spheres\": [");
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        const Sphere& s = spheres.spheres()[i];
        const Vec3d c = s.centre + meta.offset;
        buf.append(i ? ",\n  [" : "\n  [");
        for (int a = 0; a < 3; ++a) {
            buf.put_number(c[a]);
            buf.put(',');
        }
        buf.put_number(s.radius);
        buf.put(']');
    }
    buf.append(spheres.empty() ? "]\n}\n" : "\n ]\n}\n");
    buf.flush();
}

void write_collision_report_json(std::ostream& out, const CollisionSpheres& spheres,
                                 const RobotModel& robot, std::span<const LinkClearance> results,
                                 const CollisionRequest& request, const ResultMeta& meta) {
    Json links = Json::array();
    double min_clearance = kNoClearanceLimit;
    std::size_t colliding = 0;
    for (std::size_t i = 0; i < robot.links.size() && i < results.size(); ++i) {
        const RobotLink& link = robot.links[i];
        const LinkClearance& r = results[i];
        Json l = {{"name", link.name},
                  {"type", link_kind_name(link.kind)},
                  {"clearance", length_or_null(r.proximity.clearance)},
                  {"collides", r.collides}};
        if (r.proximity.nearest >= 0) {
            const Sphere& s = spheres.spheres()[static_cast<std::size_t>(r.proximity.nearest)];
            l["nearest_surface"] = r.proximity.nearest;
            l["nearest_home"] = vec_json(s.centre + meta.offset);
            l["nearest_radius"] = s.radius;
        } else {
            l["nearest_surface"] = nullptr;
        }
        links.push_back(std::move(l));
        min_clearance = std::min(min_clearance, r.proximity.clearance);
        colliding += r.collides ? 1 : 0;
    }
    const Json j = {
        {"format", "surfgrow-collision-report"},
        {"version", 1},
        {"units", meta.units},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"robot", request.robot},
        {"tolerance", request.tolerance},
        {"environment_spheres", spheres.size()},
        {"collides", colliding > 0},
        {"colliding_links", colliding},
        {"min_clearance", length_or_null(min_clearance)},
        {"links", links},
    };
    out << j.dump(1) << "\n";
}

}  // namespace surfgrow::io
