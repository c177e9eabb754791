#include "result_layers.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Why a file is not valid; turned into Error(kMalformedInput) naming the file.
struct Bad : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::optional<json> read_json(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return std::nullopt;
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(ErrorCode::kCannotOpen, cat({"cannot open ", file.string()}));
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw Error(ErrorCode::kMalformedInput,
                    cat({file.string(), ": not valid JSON: ", e.what()}));
    }
}

// "format" and "units", where the file has them, must match.
void check_head(const json& j, std::string_view format, const io::StoredResult& result) {
    if (!j.is_object()) throw Bad("not a JSON object");
    if (j.contains("format") && j["format"] != format)
        throw Bad(cat({"\"format\" is not \"", format, "\""}));
    if (j.contains("units") && j["units"] != result.meta.units)
        throw Bad(cat({"lengths are in ", j["units"].dump(), " but surfaces.json's are in \"",
                       result.meta.units, "\""}));
}

// A position in file coordinates, into the result's frame.
Vec3d point(const json& j, const io::StoredResult& result) {
    if (!j.is_array() || j.size() != 3) throw Bad("a position is not [x, y, z]");
    const Vec3d p(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
    if (!p.allFinite()) throw Bad("a position is not finite");
    return p - result.meta.offset;
}

std::vector<Vec3d> polygon(const json& j, const io::StoredResult& result) {
    if (!j.is_array()) throw Bad("a polygon is not a list of [x, y, z]");
    std::vector<Vec3d> v;
    for (const json& p : j) v.push_back(point(p, result));
    if (v.size() > 1 && v.front() == v.back()) v.pop_back();  // closed by repeating the first
    if (v.size() < 3) throw Bad("a polygon has fewer than 3 vertices");
    return v;
}

std::vector<BoundPlane> parse_planes(const json& j, const io::StoredResult& result) {
    check_head(j, "surfgrow-planes", result);
    std::vector<BoundPlane> planes;
    for (const json& jp : j.at("planes")) {
        BoundPlane p;
        p.id = jp.at("id").get<std::int32_t>();
        const std::string where = cat({"plane ", std::to_string(p.id), ": "});
        try {
            const json& n = jp.at("normal");
            if (!n.is_array() || n.size() != 3) throw Bad("normal is not [x, y, z]");
            p.normal = Vec3d(n[0].get<double>(), n[1].get<double>(), n[2].get<double>());
            if (!p.normal.allFinite() || p.normal.norm() == 0)
                throw Bad("normal is not a direction");
            p.normal.normalize();
            p.boundary = polygon(jp.at("boundary"), result);
            if (jp.contains("holes"))
                for (const json& h : jp["holes"]) p.holes.push_back(polygon(h, result));
            for (const json& s : jp.at("surfaces")) {
                const auto id = s.get<std::int64_t>();
                if (id < 0 || id >= static_cast<std::int64_t>(result.surfaces.size()))
                    throw Bad(cat({"surface ", std::to_string(id), " is not in surfaces.json (",
                                   std::to_string(result.surfaces.size()), " surfaces)"}));
                p.surfaces.push_back(static_cast<std::int32_t>(id));
            }
        } catch (const Bad& e) {
            throw Bad(cat({where, e.what()}));
        }
        planes.push_back(std::move(p));
    }
    return planes;
}

CoveragePath parse_coverage(const json& j, const io::StoredResult& result) {
    check_head(j, "surfgrow-coverage", result);
    CoveragePath path;
    for (const json& g : j.at("goals")) path.goals.push_back(point(g.at("position"), result));
    return path;
}

template <class Parse>
auto read_layer(const fs::path& file, const io::StoredResult& result, Parse parse)
    -> std::optional<decltype(parse(json{}, result))> {
    const std::optional<json> j = read_json(file);
    if (!j) return std::nullopt;
    try {
        return parse(*j, result);
    } catch (const Bad& e) {
        throw Error(ErrorCode::kMalformedInput, cat({file.string(), ": ", e.what()}));
    } catch (const json::exception& e) {
        throw Error(ErrorCode::kMalformedInput,
                    cat({file.string(), ": missing or mistyped field: ", e.what()}));
    }
}

}  // namespace

ResultLayers read_result_layers(const fs::path& dir, const io::StoredResult& result) {
    ResultLayers layers;
    layers.planes = read_layer(dir / "planes.json", result, parse_planes);
    layers.coverage = read_layer(dir / "coverage.json", result, parse_coverage);
    return layers;
}

std::vector<std::int32_t> plane_of_surface(const std::vector<BoundPlane>& planes,
                                           std::size_t surface_count) {
    std::vector<std::int32_t> of(surface_count, -1);
    for (const BoundPlane& p : planes)
        for (const std::int32_t s : p.surfaces)
            if (s >= 0 && static_cast<std::size_t>(s) < surface_count && of[s] < 0) of[s] = p.id;
    return of;
}

}  // namespace surfgrow::cli
