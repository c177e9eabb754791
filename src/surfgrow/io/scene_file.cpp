#include "surfgrow/io/scene_file.hpp"

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <ostream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io {

using nlohmann::json;
namespace sc = surfgrow::scanner;

namespace {

constexpr std::size_t kMaxSceneFileBytes = 256u << 20;

// Field access with errors that say where: "scene.json: primitive 3 ('bolt'): ...".
class Fields {
  public:
    Fields(const json& j, std::string where) : j_(j), where_(std::move(where)) {
        if (!j_.is_object()) detail::malformed(where_, "must be a JSON object");
    }
    [[noreturn]] void fail(std::string_view why) const { detail::malformed(where_, why); }
    void only(std::initializer_list<std::string_view> keys) const {
        for (const auto& [key, value] : j_.items()) {
            bool known = false;
            for (const auto k : keys) known = known || key == k;
            if (!known) fail(cat({"unknown key '", key, "'"}));
        }
    }
    [[nodiscard]] bool has(const char* key) const { return j_.contains(key); }
    [[nodiscard]] const json& at(const char* key) const {
        if (!j_.contains(key)) fail(cat({"missing '", key, "'"}));
        return j_.at(key);
    }
    [[nodiscard]] double number(const char* key) const {
        const json& v = at(key);
        if (!v.is_number()) fail(cat({"'", key, "' must be a number"}));
        return v.get<double>();
    }
    [[nodiscard]] std::string text(const char* key) const {
        const json& v = at(key);
        if (!v.is_string()) fail(cat({"'", key, "' must be a string"}));
        return v.get<std::string>();
    }
    [[nodiscard]] bool boolean(const char* key, bool fallback) const {
        if (!has(key)) return fallback;
        const json& v = at(key);
        if (!v.is_boolean()) fail(cat({"'", key, "' must be true or false"}));
        return v.get<bool>();
    }
    template <int N>
    [[nodiscard]] Eigen::Matrix<double, N, 1> vec(const char* key) const {
        const json& v = at(key);
        if (!v.is_array() || v.size() != N)
            fail(cat({"'", key, "' must be an array of ", std::to_string(N), " numbers"}));
        Eigen::Matrix<double, N, 1> out;
        for (int i = 0; i < N; ++i) {
            if (!v[static_cast<std::size_t>(i)].is_number())
                fail(cat({"'", key, "' must be an array of ", std::to_string(N), " numbers"}));
            out[i] = v[static_cast<std::size_t>(i)].get<double>();
        }
        return out;
    }
    [[nodiscard]] Mat3d matrix3(const char* key) const {
        const json& v = at(key);
        if (!v.is_array() || v.size() != 3) fail(cat({"'", key, "' must be 3 rows of 3 numbers"}));
        Mat3d m;
        for (int r = 0; r < 3; ++r) {
            const json& row = v[static_cast<std::size_t>(r)];
            if (!row.is_array() || row.size() != 3)
                fail(cat({"'", key, "' must be 3 rows of 3 numbers"}));
            for (int c = 0; c < 3; ++c) {
                if (!row[static_cast<std::size_t>(c)].is_number())
                    fail(cat({"'", key, "' must be 3 rows of 3 numbers"}));
                m(r, c) = row[static_cast<std::size_t>(c)].get<double>();
            }
        }
        return m;
    }
    [[nodiscard]] const std::string& where() const { return where_; }

  private:
    const json& j_;
    std::string where_;
};

Vec3d rpy_deg_to_rad(const Vec3d& deg) {
    return {sc::deg_to_rad(deg.x()), sc::deg_to_rad(deg.y()), sc::deg_to_rad(deg.z())};
}

sc::Primitive parse_primitive(const json& j, std::string_view file, std::size_t index) {
    std::string where = cat({file, ": primitive ", std::to_string(index)});
    if (j.is_object() && j.contains("name") && j.at("name").is_string())
        where = cat({where, " ('", j.at("name").get<std::string>(), "')"});
    const Fields f(j, where);
    sc::Primitive p;
    if (f.has("name")) p.name = f.text("name");
    const std::string type = f.text("type");
    if (type == "rectangle") {
        f.only({"type", "name", "center", "u_axis", "v_axis", "size"});
        const Eigen::Vector2d size = f.vec<2>("size");
        p.shape = sc::Rectangle{f.vec<3>("center"), f.vec<3>("u_axis"), f.vec<3>("v_axis"),
                                0.5 * size.x(), 0.5 * size.y()};
    } else if (type == "box") {
        f.only({"type", "name", "min", "max", "center", "size", "rpy_deg", "rotation"});
        sc::Box b;
        if (f.has("min") || f.has("max")) {
            if (f.has("center") || f.has("size") || f.has("rpy_deg") || f.has("rotation"))
                f.fail("a box has either 'min' and 'max', or 'center' and 'size'");
            b = sc::Box::from_min_max(f.vec<3>("min"), f.vec<3>("max"));
        } else {
            if (f.has("rpy_deg") && f.has("rotation"))
                f.fail("a box has 'rpy_deg' or 'rotation', not both");
            b.center = f.vec<3>("center");
            b.half_size_m = 0.5 * f.vec<3>("size");
            if (f.has("rpy_deg"))
                b.rotation = sc::rotation_from_rpy(rpy_deg_to_rad(f.vec<3>("rpy_deg")));
            if (f.has("rotation")) b.rotation = f.matrix3("rotation");
        }
        p.shape = b;
    } else if (type == "cylinder") {
        f.only({"type", "name", "base", "top", "radius", "capped"});
        p.shape = sc::Cylinder{f.vec<3>("base"), f.vec<3>("top"), f.number("radius"),
                               f.boolean("capped", true)};
    } else {
        f.fail(cat({"unknown primitive type '", type, "' (rectangle, box or cylinder)"}));
    }
    return p;
}

using ojson = nlohmann::ordered_json;

ojson vec_json(const Vec3d& v) {
    return ojson::array({v.x(), v.y(), v.z()});
}

}  // namespace

sc::SceneDescription parse_scene_json(std::string_view text, std::string_view name) {
    detail::check_json_limits(text, name);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        detail::malformed(name, cat({"invalid JSON: ", e.what()}));
    }
    const Fields top(doc, std::string(name));
    top.only({"format", "version", "name", "primitives", "scanner"});
    if (top.text("format") != "surfgrow-scene") top.fail("'format' must be \"surfgrow-scene\"");
    if (top.number("version") != kSceneFormatVersion)
        top.fail(cat({"unsupported scene version ", num(top.number("version")),
                      " (this surfgrow reads version 1)"}));
    sc::SceneDescription scene;
    if (top.has("name")) scene.name = top.text("name");
    const json& prims = top.at("primitives");
    if (!prims.is_array()) top.fail("'primitives' must be an array");
    for (std::size_t i = 0; i < prims.size(); ++i)
        scene.primitives.push_back(parse_primitive(prims[i], name, i));
    if (top.has("scanner")) {
        const Fields s(top.at("scanner"), cat({name, ": scanner"}));
        s.only({"pose", "step"});
        if (s.has("pose")) scene.scanner.home = pose_from_json(s.at("pose"), s.where());
        if (s.has("step")) scene.scanner.step_m = s.vec<3>("step");
    }
    try {
        (void)sc::Scene(scene);  // value checks (sizes, axes, rotations)
    } catch (const Error& e) {
        detail::rethrow_in(name, e);
    }
    return scene;
}

sc::SceneDescription read_scene_file(const std::filesystem::path& path) {
    const std::string text = detail::read_file_capped(path, kMaxSceneFileBytes, "a scene file");
    return parse_scene_json(text, path.string());
}

std::string scene_to_json(const sc::SceneDescription& scene) {
    (void)sc::Scene(scene);
    ojson prims = ojson::array();
    for (const sc::Primitive& p : scene.primitives) {
        ojson j;
        j["type"] = "";
        if (!p.name.empty()) j["name"] = p.name;
        if (const auto* r = std::get_if<sc::Rectangle>(&p.shape)) {
            j["type"] = "rectangle";
            j["center"] = vec_json(r->center);
            j["u_axis"] = vec_json(r->u_axis);
            j["v_axis"] = vec_json(r->v_axis);
            j["size"] = ojson::array({2 * r->half_u_m, 2 * r->half_v_m});
        } else if (const auto* b = std::get_if<sc::Box>(&p.shape)) {
            j["type"] = "box";
            j["center"] = vec_json(b->center);
            j["size"] = vec_json(2 * b->half_size_m);
            if (!b->rotation.isIdentity(0.0)) {
                ojson rows = ojson::array();
                for (int row = 0; row < 3; ++row)
                    rows.push_back(ojson::array(
                        {b->rotation(row, 0), b->rotation(row, 1), b->rotation(row, 2)}));
                j["rotation"] = rows;
            }
        } else {
            const auto& c = std::get<sc::Cylinder>(p.shape);
            j["type"] = "cylinder";
            j["base"] = vec_json(c.base);
            j["top"] = vec_json(c.top);
            j["radius"] = c.radius_m;
            if (!c.capped) j["capped"] = false;
        }
        prims.push_back(j);
    }
    ojson matrix = ojson::array();
    for (int r = 0; r < 4; ++r) {
        ojson row = ojson::array();
        for (int c = 0; c < 4; ++c) row.push_back(scene.scanner.home.matrix()(r, c));
        matrix.push_back(row);
    }
    ojson doc;
    doc["format"] = "surfgrow-scene";
    doc["version"] = kSceneFormatVersion;
    doc["name"] = scene.name;
    doc["scanner"]["pose"]["matrix"] = matrix;
    doc["scanner"]["step"] = vec_json(scene.scanner.step_m);
    doc["primitives"] = prims;
    return doc.dump(2) + "\n";
}

void write_scene_file(const std::filesystem::path& path, const sc::SceneDescription& scene) {
    std::string text;
    try {
        text = scene_to_json(scene);
    } catch (const Error& e) {
        detail::rethrow_in(path.string(), e);
    }
    write_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace surfgrow::io
