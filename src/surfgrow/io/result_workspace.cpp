#include "surfgrow/io/result_workspace.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace {

Vec3d vec_of(const nlohmann::json& j) {
    if (!j.is_array() || j.size() != 3) throw std::invalid_argument("expected [x, y, z]");
    const Vec3d v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
    if (!v.allFinite()) throw std::invalid_argument("expected finite [x, y, z]");
    return v;
}

}  // namespace

void read_workspace_parameters(const std::filesystem::path& surfaces_json, GrowerConfig& config) {
    std::ifstream in(surfaces_json, std::ios::binary);
    if (!in) throw Error(ErrorCode::kCannotOpen, cat({"cannot open ", surfaces_json.string()}));
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        const nlohmann::json& p = j.at("parameters");
        if (p.contains("viewpoint")) config.viewpoint = vec_of(p["viewpoint"]);
        if (p.contains("crop_box")) {
            Aabb box;
            box.min = vec_of(p["crop_box"].at("min"));
            box.max = vec_of(p["crop_box"].at("max"));
            config.crop.box = box;
        }
        if (p.contains("crop_radius")) config.crop.radius = p["crop_radius"].get<double>();
        if (p.contains("crop_center")) config.crop.center = vec_of(p["crop_center"]);
    } catch (const std::exception& e) {
        throw Error(ErrorCode::kMalformedInput,
                    cat({surfaces_json.string(), ": bad workspace parameters: ", e.what()}));
    }
}

}  // namespace surfgrow::io
