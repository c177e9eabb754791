#include "surfgrow/io/robot_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/file_bytes.hpp"
#include "surfgrow/io/io_error.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io {

namespace {

using Json = nlohmann::json;

double unit_metres(const std::string& unit) {
    if (unit == "m") return 1.0;
    if (unit == "cm") return 0.01;
    if (unit == "mm") return 0.001;
    return 0.0;
}

struct LinkParser {
    std::string_view source;
    std::string where;  // "link 2 ('arm')"
    double scale = 1.0;
    Vec3d offset = Vec3d::Zero();

    [[noreturn]] void fail(std::string_view what) const {
        throw_malformed(source, cat({where, ": ", what}));
    }
    const Json& field(const Json& link, const char* name) const {
        const auto it = link.find(name);
        if (it == link.end()) fail(cat({"missing \"", name, "\""}));
        return *it;
    }
    double length(const Json& j, const char* name) const {
        if (!j.is_number()) fail(cat({"\"", name, "\" must be a number"}));
        const double v = j.get<double>();
        if (!std::isfinite(v)) fail(cat({"\"", name, "\" must be finite"}));
        return v * scale;
    }
    Vec3d position(const Json& j, const char* name) const {
        if (!j.is_array() || j.size() != 3)
            fail(cat({"\"", name, "\" must be [x, y, z], three numbers"}));
        Vec3d v;
        for (int a = 0; a < 3; ++a) v[a] = length(j[static_cast<std::size_t>(a)], name);
        return v - offset;
    }
    double radius(const Json& link) const {
        const double r = length(field(link, "radius"), "radius");
        if (!(r > 0)) fail(cat({"the radius must be > 0, got ", num(r / scale)}));
        return r;
    }
};

}  // namespace

RobotModel parse_robot_json(std::string_view text, std::string_view source,
                            const RobotFrame& frame) {
    detail::check_json_limits(text, source);
    Json j;
    try {
        j = Json::parse(text.begin(), text.end());
    } catch (const Json::exception& e) {
        throw_malformed(source, cat({"not valid JSON: ", e.what()}));
    }
    if (!j.is_object())
        throw_malformed(source, "expected a JSON object with \"units\" and \"links\"");
    for (const auto& [key, value] : j.items()) {
        if (key != "format" && key != "version" && key != "units" && key != "links" &&
            key != "comment")
            throw_malformed(source, cat({"unknown field \"", key, "\""}));
    }
    if (j.contains("format") && j["format"] != "surfgrow-robot")
        throw_malformed(source, "\"format\" must be \"surfgrow-robot\"");
    if (!j.contains("units") || !j["units"].is_string())
        throw_malformed(source, "missing \"units\" (\"m\", \"cm\" or \"mm\")");
    const std::string units = j["units"].get<std::string>();
    const double metres = unit_metres(units);
    if (metres == 0)
        throw_malformed(source, cat({"unknown units '", units, "' (use m, cm or mm)"}));
    if (!j.contains("links") || !j["links"].is_array() || j["links"].empty())
        throw_malformed(source, "missing \"links\": a non-empty list of spheres and capsules");

    LinkParser p{source, {}, metres / frame.metres_per_unit, frame.offset};
    RobotModel robot;
    std::set<std::string> names;
    const Json& links = j["links"];
    for (std::size_t i = 0; i < links.size(); ++i) {
        const Json& link = links[i];
        p.where = cat({"link ", std::to_string(i)});
        if (!link.is_object()) p.fail("expected an object with \"name\", \"type\" and its shape");
        const Json& name = p.field(link, "name");
        if (!name.is_string() || name.get<std::string>().empty())
            p.fail("\"name\" must be a non-empty string");
        RobotLink out;
        out.name = name.get<std::string>();
        p.where = cat({"link ", std::to_string(i), " ('", out.name, "')"});
        if (!names.insert(out.name).second) p.fail("the name is used by an earlier link");
        const Json& type = p.field(link, "type");
        if (!type.is_string()) p.fail("\"type\" must be \"sphere\" or \"capsule\"");
        const std::string t = type.get<std::string>();
        if (t == "sphere") {
            if (link.contains("centre") && link.contains("center"))
                p.fail("give \"centre\" or \"center\", not both");
            for (const auto& [key, value] : link.items())
                if (key != "name" && key != "type" && key != "centre" && key != "center" &&
                    key != "radius")
                    p.fail(cat({"unknown field \"", key, "\" for a sphere"}));
            const char* c = link.contains("center") ? "center" : "centre";
            const Vec3d centre = p.position(p.field(link, c), c);
            out.kind = RobotLink::Kind::kSphere;
            out.shape = {centre, centre, p.radius(link)};
        } else if (t == "capsule") {
            for (const auto& [key, value] : link.items())
                if (key != "name" && key != "type" && key != "a" && key != "b" && key != "radius")
                    p.fail(cat({"unknown field \"", key, "\" for a capsule"}));
            out.kind = RobotLink::Kind::kCapsule;
            out.shape = {p.position(p.field(link, "a"), "a"), p.position(p.field(link, "b"), "b"),
                         p.radius(link)};
        } else {
            p.fail(cat({"unknown type '", t, "' (use sphere or capsule)"}));
        }
        if (!is_valid(out.shape)) p.fail("the shape does not fit in double precision");
        robot.links.push_back(std::move(out));
    }
    return robot;
}

RobotModel read_robot_json(const std::filesystem::path& file, const RobotFrame& frame) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_robot_json(bytes.view(), file.string(), frame);
}

}  // namespace surfgrow::io
