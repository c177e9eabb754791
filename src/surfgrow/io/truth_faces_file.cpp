#include "surfgrow/io/truth_faces_file.hpp"

#include <nlohmann/json.hpp>
#include <ostream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io {

namespace sc = surfgrow::scanner;
using ojson = nlohmann::ordered_json;
using nlohmann::json;

namespace {

constexpr std::size_t kMaxTruthFileBytes = 512u << 20;

ojson vec_json(const Vec3d& v) {
    return ojson::array({v.x(), v.y(), v.z()});
}

const char* kind_name(sc::FaceKind k) {
    switch (k) {
        case sc::FaceKind::kRectangle:
            return "rectangle";
        case sc::FaceKind::kDisc:
            return "disc";
        case sc::FaceKind::kCylinder:
            return "cylinder";
    }
    return "rectangle";
}

Vec3d vec_of(const json& f, const char* key, std::string_view where) {
    if (!f.contains(key) || !f.at(key).is_array() || f.at(key).size() != 3)
        detail::malformed(where, cat({"'", key, "' must be an array of 3 numbers"}));
    Vec3d v;
    for (int i = 0; i < 3; ++i) {
        const json& x = f.at(key)[static_cast<std::size_t>(i)];
        if (!x.is_number()) detail::malformed(where, cat({"'", key, "' must hold numbers"}));
        v[i] = x.get<double>();
    }
    return v;
}

double num_of(const json& f, const char* key, std::string_view where) {
    if (!f.contains(key) || !f.at(key).is_number())
        detail::malformed(where, cat({"'", key, "' must be a number"}));
    return f.at(key).get<double>();
}

}  // namespace

std::string truth_faces_to_json(const sc::Scene& scene) {
    ojson faces = ojson::array();
    const auto& prims = scene.description().primitives;
    for (const sc::Face& f : scene.faces()) {
        ojson j;
        j["id"] = f.id;
        j["primitive"] = f.primitive;
        j["primitive_name"] = prims[static_cast<std::size_t>(f.primitive)].name;
        j["kind"] = kind_name(f.kind);
        j["center"] = vec_json(f.center);
        if (f.planar()) {
            j["normal"] = vec_json(f.normal);
            j["d"] = f.plane().d + 0.0;  // no "-0"
        } else {
            j["axis"] = vec_json(f.normal);
        }
        switch (f.kind) {
            case sc::FaceKind::kRectangle:
                j["u_axis"] = vec_json(f.u_axis);
                j["v_axis"] = vec_json(f.v_axis);
                j["size"] = ojson::array({2 * f.half_u_m, 2 * f.half_v_m});
                break;
            case sc::FaceKind::kDisc:
                j["radius"] = f.half_u_m;
                break;
            case sc::FaceKind::kCylinder:
                j["radius"] = f.half_u_m;
                j["length"] = 2 * f.half_v_m;
                break;
        }
        faces.push_back(j);
    }
    // One face per line: readable, and a fraction of the size of a fully indented dump.
    std::string out = cat({"{\"format\": \"surfgrow-truth-faces\", \"version\": 1, \"scene\": ",
                           ojson(scene.description().name).dump(), ", \"faces\": [\n"});
    for (std::size_t i = 0; i < faces.size(); ++i) {
        out += faces[i].dump();
        out += i + 1 < faces.size() ? ",\n" : "\n";
    }
    out += "]}\n";
    return out;
}

void write_truth_faces(const std::filesystem::path& path, const sc::Scene& scene) {
    const std::string text = truth_faces_to_json(scene);
    write_atomically(path, [&](std::ostream& out) { out << text; });
}

std::vector<sc::Face> parse_truth_faces_json(std::string_view text, std::string_view name) {
    detail::check_json_limits(text, name);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        detail::malformed(name, cat({"invalid JSON: ", e.what()}));
    }
    if (!doc.is_object() || !doc.contains("format") || doc.at("format") != "surfgrow-truth-faces")
        detail::malformed(name,
                          "not a surfgrow truth-faces file ('format' must be "
                          "\"surfgrow-truth-faces\")");
    if (!doc.contains("version") || doc.at("version") != 1)
        detail::malformed(name, "unsupported truth-faces version (this surfgrow reads 1)");
    if (!doc.contains("faces") || !doc.at("faces").is_array())
        detail::malformed(name, "'faces' must be an array");
    std::vector<sc::Face> out;
    for (const json& j : doc.at("faces")) {
        const std::string where = cat({name, ": face ", std::to_string(out.size())});
        if (!j.is_object()) detail::malformed(where, "must be an object");
        sc::Face f;
        if (num_of(j, "id", where) != static_cast<double>(out.size()))
            detail::malformed(where, "face ids must be 0, 1, 2, ... in order");
        f.id = static_cast<std::int32_t>(out.size());
        const double prim = num_of(j, "primitive", where);
        if (!(prim >= 0 && prim <= 1e9)) detail::malformed(where, "bad 'primitive'");
        f.primitive = static_cast<std::int32_t>(prim);
        const std::string kind = j.contains("kind") && j.at("kind").is_string()
                                     ? j.at("kind").get<std::string>()
                                     : std::string();
        f.center = vec_of(j, "center", where);
        if (kind == "rectangle") {
            f.kind = sc::FaceKind::kRectangle;
            f.normal = vec_of(j, "normal", where);
            f.u_axis = vec_of(j, "u_axis", where);
            f.v_axis = vec_of(j, "v_axis", where);
            if (!j.contains("size") || !j.at("size").is_array() || j.at("size").size() != 2 ||
                !j.at("size")[0].is_number() || !j.at("size")[1].is_number())
                detail::malformed(where, "'size' must be an array of 2 numbers");
            f.half_u_m = 0.5 * j.at("size")[0].get<double>();
            f.half_v_m = 0.5 * j.at("size")[1].get<double>();
        } else if (kind == "disc") {
            f.kind = sc::FaceKind::kDisc;
            f.normal = vec_of(j, "normal", where);
            f.half_u_m = f.half_v_m = num_of(j, "radius", where);
        } else if (kind == "cylinder") {
            f.kind = sc::FaceKind::kCylinder;
            f.normal = vec_of(j, "axis", where);
            f.half_u_m = num_of(j, "radius", where);
            f.half_v_m = 0.5 * num_of(j, "length", where);
        } else {
            detail::malformed(where, "'kind' must be rectangle, disc or cylinder");
        }
        out.push_back(f);
    }
    return out;
}

std::vector<sc::Face> read_truth_faces(const std::filesystem::path& path) {
    const std::string text =
        detail::read_file_capped(path, kMaxTruthFileBytes, "a truth-faces file");
    return parse_truth_faces_json(text, path.string());
}

}  // namespace surfgrow::io
