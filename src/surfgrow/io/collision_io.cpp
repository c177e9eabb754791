#include "surfgrow/io/collision_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "surfgrow/io/fixed_ply_header.hpp"

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
    const Json doc = {
        {"format", "surfgrow-collision-spheres"},
        {"version", 2},
        {"units", meta.units},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"what",
         "one sphere per surface: centre at its home point, radius its neighbourhood "
         "radius (paper 5.5); id = surface id; the spheres are the vertices (x, y, z, radius) "
         "of spheres_file"},
        {"count", spheres.size()},
        {"radius", {{"min", rmin}, {"max", rmax}}},
        {"spheres_file", kCollisionSpheresFile},
    };
    out << doc.dump(1) << '\n';
}

void write_collision_spheres_ply(std::ostream& out, const CollisionSpheres& spheres,
                                 const ResultMeta& meta) {
    const bool wide = meta.offset != Vec3d::Zero();  // keep georeferenced precision
    const std::string pos = wide ? "double " : "float ";
    const std::vector<std::string> layout = {pos + "x", pos + "y", pos + "z", "float radius"};
    const std::string head =
        fixed_ply_head("surfgrow collision spheres: one vertex per sphere at its centre",
                       meta.units, meta.result_id, spheres.size(), layout);
    std::string body(spheres.size() * record_bytes(layout), '\0');
    char* at = body.data();
    auto put = [&at](auto v) {
        std::memcpy(at, &v, sizeof v);  // little-endian hosts (results_io.cpp checks)
        at += sizeof v;
    };
    for (const Sphere& s : spheres.spheres()) {
        const Vec3d c = s.centre + meta.offset;
        for (int a = 0; a < 3; ++a) {
            if (wide)
                put(c[a]);
            else
                put(static_cast<float>(c[a]));
        }
        put(static_cast<float>(s.radius));
    }
    out << head << body;
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
