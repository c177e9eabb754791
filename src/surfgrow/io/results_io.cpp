#include "surfgrow/io/results_io.hpp"

#include <bit>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/file_bytes.hpp"
#include "surfgrow/io/fixed_ply_header.hpp"
#include "surfgrow/io/json_fields.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io {

using json_fields::integer_at;

namespace {

// Shortest round-trip decimal; JSON has no infinity or NaN, so those become null.
void put_number(std::string& out, double v) {
    if (!std::isfinite(v)) {
        out += "null";
        return;
    }
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

static_assert(std::endian::native == std::endian::little,
              "binary writers assume a little-endian host");

[[noreturn]] void malformed(const std::filesystem::path& file, std::string_view what) {
    throw Error(ErrorCode::kMalformedInput, cat({file.string(), ": ", what}));
}

Vec3d vec_of(const nlohmann::json& j) {
    if (!j.is_array() || j.size() != 3) throw std::invalid_argument("expected [x, y, z]");
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

}  // namespace

namespace {

// FNV-style word mixing: deterministic across platforms and runs, a few ms for a million labels.
class Hash64 {
  public:
    void add(std::uint64_t v) {
        h_ ^= v;
        h_ *= 0x100000001b3ULL;
        h_ ^= h_ >> 29;
    }
    void add(double v) { add(std::bit_cast<std::uint64_t>(v)); }
    void add(const Vec3d& v) {
        for (int a = 0; a < 3; ++a) add(v[a]);
    }
    void add(std::string_view s) {
        add(static_cast<std::uint64_t>(s.size()));
        for (std::size_t i = 0; i < s.size(); i += 8) {
            std::uint64_t w = 0;
            std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
            add(w);
        }
    }
    [[nodiscard]] std::string hex() const {
        char buf[17];
        std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
        return buf;
    }

  private:
    std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace

std::string result_id(const GrowResult& result, const GrowerConfig& config,
                      const ResultMeta& meta) {
    Hash64 h;
    h.add(parameters_json(config).dump());
    h.add(std::string_view(meta.units));
    h.add(meta.offset);
    h.add(static_cast<std::uint64_t>(result.surfaces.size()));
    for (const Surface& s : result.surfaces) {
        h.add(s.home);
        h.add(s.normal);
        h.add(s.radius);
        h.add(static_cast<std::uint64_t>(s.point_count));
    }
    const std::span<const std::int32_t> labels = result.labels;
    h.add(static_cast<std::uint64_t>(labels.size()));
    for (std::size_t i = 0; i < labels.size(); i += 2) {
        const auto lo = static_cast<std::uint32_t>(labels[i]);
        const auto hi = i + 1 < labels.size() ? static_cast<std::uint32_t>(labels[i + 1]) : 0u;
        h.add(std::uint64_t{hi} << 32 | lo);
    }
    return h.hex();
}

nlohmann::json parameters_json(const GrowerConfig& c) {
    nlohmann::json p = {
        {"mu", c.mu},
        {"min_pts", c.min_pts},
        {"alpha", c.alpha},
        {"plane_test", c.plane_test == PlaneTest::kPaper ? "paper" : "disk"},
        {"min_spread", c.min_spread},
        {"max_incidence_deg", c.max_incidence_deg},
        {"noise_sigmas", c.noise_sigmas},
        {"plane_tolerance", c.tolerance()},
        {"mu_max", c.max_radius()},
        {"min_new_points", c.min_new_points},
        {"pool_angle_deg", c.pool_angle_deg},
        {"pool_radius", c.pooling_radius()},
        {"attach_leftovers", c.attach_leftovers},
        {"seed", c.seed},
        {"range_band", c.range_band},
    };
    if (c.viewpoint) p["viewpoint"] = {c.viewpoint->x(), c.viewpoint->y(), c.viewpoint->z()};
    if (c.crop.box)
        p["crop_box"] = {{"min", {c.crop.box->min.x(), c.crop.box->min.y(), c.crop.box->min.z()}},
                         {"max", {c.crop.box->max.x(), c.crop.box->max.y(), c.crop.box->max.z()}}};
    if (c.crop.radius) p["crop_radius"] = *c.crop.radius;
    if (c.crop.center)
        p["crop_center"] = {c.crop.center->x(), c.crop.center->y(), c.crop.center->z()};
    return p;
}

nlohmann::json summary_json(const GrowStats& s) {
    nlohmann::json bands = nlohmann::json::array();
    for (const RangeBand& b : s.range_bands) {
        bands.push_back(
            {{"from", b.from},
             {"to", std::isfinite(b.to) ? nlohmann::json(b.to) : nlohmann::json(nullptr)},
             {"points", b.points},
             {"registered", b.registered},
             {"registered_fraction", b.points ? double(b.registered) / double(b.points) : 0.0}});
    }
    return {
        {"points_in", s.points_in},
        {"invalid_points", s.invalid_points},
        {"cropped_points", s.cropped_points},
        {"valid_points", s.valid_points},
        {"surfaces", s.surfaces},
        {"registered", s.registered},
        {"registered_fraction", s.registered_fraction()},
        {"registered_grown", s.registered_grown},
        {"registered_grown_fraction", s.registered_grown_fraction()},
        {"homes_tried", s.homes_tried},
        {"rejected_sparse", s.rejected_sparse},
        {"rejected_nonplanar", s.rejected_nonplanar},
        {"rejected_covered", s.rejected_covered},
        {"released_by_refinement", s.released_by_refinement},
        {"dropped_surfaces", s.dropped_surfaces},
        {"lone_surfaces", s.lone_surfaces},
        {"strip_surfaces", s.strip_surfaces},
        {"edge_moves", s.edge_moves},
        {"adapted_surfaces", s.adapted_surfaces},
        {"noise_sigma_by_range", {{"band", s.noise_band}, {"sigma", s.noise_sigma}}},
        {"layer_sigma_by_range", {{"band", s.layer_band}, {"sigma", s.layer_sigma}}},
        {"noise_points", s.noise_points},
        {"data_reduction", s.data_reduction()},
        {"orientation", orientation_name(s.orientation)},
        {"edge_on_points", s.edge_on_points},
        {"range_origin",
         s.range_known ? nlohmann::json{s.range_origin.x(), s.range_origin.y(), s.range_origin.z()}
                       : nlohmann::json(nullptr)},
        {"range_bands", bands},
    };
}

const char* orientation_name(OrientationSource source) {
    switch (source) {
        case OrientationSource::kScanOrigins:
            return "scan_origins";
        case OrientationSource::kViewpoint:
            return "viewpoint";
        case OrientationSource::kFrameOrigin:
            return "frame_origin";
        case OrientationSource::kUp:
            return "up";
    }
    return "up";
}

namespace {

// surfaces.ply's vertex properties, "TYPE NAME" in file order: the writer's header and what the
// reader expects. Every number in double: a command reading the folder back (planes, coverage,
// occupancy, eval) must see the surfaces exactly as grown.
std::vector<std::string> surface_layout() {
    std::vector<std::string> layout;
    auto doubles = [&](std::initializer_list<const char*> names) {
        for (const char* name : names) layout.push_back(cat({"double ", name}));
    };
    doubles({"x", "y", "z", "nx", "ny", "nz", "radius", "plane_offset"});
    layout.emplace_back("uint point_count");
    doubles({"mean_residual", "cx", "cy", "cz", "lambda_min", "lambda_mid", "lambda_max"});
    layout.emplace_back("uint neighbours");
    doubles({"tolerance", "min_x", "min_y", "min_z", "max_x", "max_y", "max_z"});
    return layout;
}

}  // namespace

void write_surfaces_ply(std::ostream& out, std::span<const Surface> surfaces,
                        const ResultMeta& meta) {
    const std::vector<std::string> layout = surface_layout();
    const std::string head = fixed_ply_head(
        "surfgrow surfaces: one vertex per surface at its home point, with its normal", meta.units,
        meta.result_id, surfaces.size(), layout);
    std::string body(surfaces.size() * record_bytes(layout), '\0');
    char* at = body.data();
    auto put = [&at](auto v) {
        std::memcpy(at, &v, sizeof v);  // little-endian hosts only (checked above)
        at += sizeof v;
    };
    auto put_vec3 = [&](const Vec3d& v) {
        for (int a = 0; a < 3; ++a) put(v[a]);
    };
    for (const Surface& s : surfaces) {
        const Vec3d home = s.home + meta.offset;
        put_vec3(home);
        put_vec3(s.normal);
        put(s.radius);
        put(-s.normal.dot(s.centroid + meta.offset));
        put(s.point_count);
        put(s.mean_residual);
        put_vec3(s.centroid + meta.offset);
        put_vec3(s.eigenvalues);
        put(s.neighbours);
        put(s.tolerance);
        put_vec3(s.bounds.empty() ? home : Vec3d(s.bounds.min + meta.offset));
        put_vec3(s.bounds.empty() ? home : Vec3d(s.bounds.max + meta.offset));
    }
    assert(at == body.data() + body.size());
    out << head << body;
}

void write_result_json(std::ostream& out, const GrowResult& result, const GrowerConfig& config,
                       const ResultMeta& meta) {
    const nlohmann::json doc = {
        {"format", "surfgrow-result"},
        {"version", 2},
        {"units", meta.units},
        {"offset", {meta.offset.x(), meta.offset.y(), meta.offset.z()}},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"parameters", parameters_json(config)},
        {"summary", summary_json(result.stats)},
        {"surfaces_file", kSurfacesFile},
    };
    out << doc.dump(1) << '\n';
}

void write_surfaces_csv(std::ostream& out, std::span<const Surface> surfaces,
                        const ResultMeta& meta) {
    std::string text =
        "id,home_x,home_y,home_z,normal_x,normal_y,normal_z,plane_d,radius,points,mean_residual,"
        "centroid_x,centroid_y,centroid_z,lambda_min,lambda_mid,lambda_max\n";
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
        const Surface& s = surfaces[k];
        const Vec3d home = s.home + meta.offset, centroid = s.centroid + meta.offset;
        text += std::to_string(k);
        auto field = [&](double v) {
            text += ',';
            put_number(text, v);
        };
        for (int a = 0; a < 3; ++a) field(home[a]);
        for (int a = 0; a < 3; ++a) field(s.normal[a]);
        field(-s.normal.dot(centroid));
        field(s.radius);
        text += ',';
        text += std::to_string(s.point_count);
        field(s.mean_residual);
        for (int a = 0; a < 3; ++a) field(centroid[a]);
        for (int a = 0; a < 3; ++a) field(s.eigenvalues[a]);
        text += '\n';
        if (text.size() > (1u << 20)) {
            out << text;
            text.clear();
        }
    }
    out << text;
}

void write_labels_bin(std::ostream& out, std::span<const std::int32_t> labels) {
    // Little-endian hosts (checked above): the array's bytes are the file.
    out.write(reinterpret_cast<const char*>(labels.data()),
              static_cast<std::streamsize>(labels.size_bytes()));
}

void write_labels_txt(std::ostream& out, std::span<const std::int32_t> labels) {
    std::string text;
    text.reserve(std::min<std::size_t>(labels.size(), 1u << 18) * 7);
    char buf[16];
    for (const std::int32_t l : labels) {
        const auto r = std::to_chars(buf, buf + sizeof buf, l);
        text.append(buf, r.ptr);
        text += '\n';
        if (text.size() > (1u << 20)) {
            out << text;
            text.clear();
        }
    }
    out << text;
}

StoredResult read_result_json(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw Error(ErrorCode::kCannotOpen,
                    cat({"cannot open ", file.string(), " (is this a surfgrow result?)"}));
    const FileBytes bytes = FileBytes::read(file);
    StoredResult r = parse_result_json(bytes.view(), file.string());
    if (r.surfaces_file.empty()) return r;  // version 1: surfaces inline
    const std::filesystem::path surfaces_path = file.parent_path() / r.surfaces_file;
    StoredSurfaces s = read_surfaces_ply(surfaces_path, r.meta.offset);
    if (s.surfaces.size() != r.stats.surfaces)
        malformed(surfaces_path,
                  cat({"holds ", std::to_string(s.surfaces.size()), " surfaces but ",
                       file.filename().string(), " says ", std::to_string(r.stats.surfaces)}));
    if (s.result_id != r.meta.result_id)
        malformed(surfaces_path,
                  cat({"belongs to another result (result_id \"", s.result_id, "\", ",
                       file.filename().string(), " has \"", r.meta.result_id,
                       "\"): the folder is a mix of two runs; run `surfgrow grow` again"}));
    r.surfaces = std::move(s.surfaces);
    return r;
}

StoredSurfaces read_surfaces_ply(const std::filesystem::path& file, const Vec3d& offset) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_surfaces_ply(bytes.view(), file.string(), offset);
}

StoredSurfaces parse_surfaces_ply(std::string_view all, std::string_view source,
                                  const Vec3d& offset) {
    const std::filesystem::path file(source);
    const FixedPlyHeader h = read_fixed_ply_header(all, source);
    const std::vector<std::string> layout = surface_layout();
    if (!h.is_vertex_layout(layout))
        malformed(file,
                  "not a surfgrow surfaces file (expected the layout surfaces.ply is written in; "
                  "folders written before version 2 keep their surfaces in surfaces.json)");
    const std::uint64_t count = h.elements[0].second;
    const std::size_t size = record_bytes(layout);
    if (count > all.size() / size || all.size() - h.body != count * size)
        malformed(file, cat({"truncated or too long: the header promises ", std::to_string(count),
                             " surfaces"}));
    StoredSurfaces r;
    r.result_id = h.result_id;
    const char* p = all.data() + h.body;
    auto take = [&p](auto& v) {
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
    };
    auto vec3 = [&] {
        Vec3d v;
        for (int a = 0; a < 3; ++a) take(v[a]);
        return v;
    };
    r.surfaces.resize(static_cast<std::size_t>(count));
    for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
        Surface& s = r.surfaces[k];
        s.home = vec3() - offset;
        s.normal = vec3();
        take(s.radius);
        double plane_offset;  // derived from normal and centroid; read past
        take(plane_offset);
        take(s.point_count);
        take(s.mean_residual);
        s.centroid = vec3() - offset;
        s.eigenvalues = vec3();
        take(s.neighbours);
        take(s.tolerance);
        const Vec3d lo = vec3() - offset, hi = vec3() - offset;
        s.bounds.add(lo);
        s.bounds.add(hi);
        const bool finite = s.home.allFinite() && s.normal.allFinite() && s.centroid.allFinite() &&
                            s.eigenvalues.allFinite() && std::isfinite(s.radius) &&
                            std::isfinite(s.mean_residual) && std::isfinite(s.tolerance) &&
                            lo.allFinite() && hi.allFinite();
        if (!finite) malformed(file, cat({"surface ", std::to_string(k), " is not finite"}));
        if (std::abs(s.normal.norm() - 1.0) > 1e-6)
            malformed(file,
                      cat({"surface ", std::to_string(k), ": its normal is not a unit vector"}));
    }
    return r;
}

StoredResult parse_result_json(std::string_view text, std::string_view source) {
    const std::filesystem::path file(source);
    detail::check_json_limits(text, source);
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        malformed(file, cat({"not valid JSON: ", e.what()}));
    }
    StoredResult r;
    try {
        if (j.value("format", "") != "surfgrow-result")
            malformed(file, "not a surfgrow result (no \"format\": \"surfgrow-result\")");
        r.meta.units = j.at("units").get<std::string>();
        r.meta.offset = vec_of(j.at("offset"));
        r.meta.input = j.value("input", "");
        r.meta.result_id = j.value("result_id", "");
        const auto& p = j.at("parameters");
        r.config.mu = p.at("mu").get<double>();
        r.config.min_pts = integer_at<int>(p, "min_pts");
        r.config.alpha = p.at("alpha").get<double>();
        r.config.plane_test =
            p.value("plane_test", "paper") == "disk" ? PlaneTest::kDisk : PlaneTest::kPaper;
        r.config.plane_tolerance = p.at("plane_tolerance").get<double>();
        r.config.adaptive_factor = p.at("mu_max").get<double>() / r.config.mu;
        r.config.seed = integer_at<std::uint64_t>(p, "seed");
        // The workspace: the occupancy grid needs it to index exactly the grown points again.
        auto finite_vec = [&](const nlohmann::json& v, std::string_view what) {
            const Vec3d x = vec_of(v);
            if (!x.allFinite()) malformed(file, cat({"parameters.", what, " is not finite"}));
            return x;
        };
        if (p.contains("viewpoint")) r.config.viewpoint = finite_vec(p["viewpoint"], "viewpoint");
        if (p.contains("crop_box")) {
            Aabb box;
            box.min = finite_vec(p["crop_box"].at("min"), "crop_box");
            box.max = finite_vec(p["crop_box"].at("max"), "crop_box");
            r.config.crop.box = box;
        }
        if (p.contains("crop_radius")) r.config.crop.radius = p["crop_radius"].get<double>();
        if (p.contains("crop_center"))
            r.config.crop.center = finite_vec(p["crop_center"], "crop_center");
        const auto& s = j.at("summary");
        r.stats.points_in = integer_at<std::uint64_t>(s, "points_in");
        r.stats.valid_points = integer_at<std::uint64_t>(s, "valid_points");
        r.stats.invalid_points = integer_at<std::uint64_t>(s, "invalid_points");
        r.stats.cropped_points = integer_at<std::uint64_t>(s, "cropped_points");
        r.stats.surfaces = integer_at<std::uint64_t>(s, "surfaces");
        r.stats.registered = integer_at<std::uint64_t>(s, "registered");
        r.stats.registered_grown = integer_at<std::uint64_t>(s, "registered_grown");
        r.stats.noise_points = integer_at<std::uint64_t>(s, "noise_points");
        const std::string orientation = s.at("orientation").get<std::string>();
        bool known = false;
        for (OrientationSource o : {OrientationSource::kScanOrigins, OrientationSource::kViewpoint,
                                    OrientationSource::kFrameOrigin, OrientationSource::kUp})
            if (orientation == orientation_name(o)) {
                r.stats.orientation = o;
                known = true;
            }
        if (!known) malformed(file, cat({"summary.orientation is unknown ('", orientation, "')"}));
        if (j.contains("surfaces_file")) {  // version 2: the surfaces are in their own file
            const auto& f = j.at("surfaces_file");
            if (!f.is_string()) throw std::invalid_argument("surfaces_file is not a file name");
            r.surfaces_file = f.get<std::string>();
            if (r.surfaces_file.empty() || r.surfaces_file == "." || r.surfaces_file == ".." ||
                r.surfaces_file.find_first_of("/\\") != std::string::npos)
                throw std::invalid_argument("surfaces_file is not the name of a file beside it");
            return r;
        }
        for (const auto& js : j.at("surfaces")) {
            Surface surf;
            surf.normal = vec_of(js.at("normal"));
            surf.home = vec_of(js.at("home")) - r.meta.offset;
            surf.centroid = vec_of(js.at("centroid")) - r.meta.offset;
            surf.eigenvalues = vec_of(js.at("eigenvalues"));
            surf.radius = js.at("radius").get<double>();
            surf.neighbours = integer_at<std::uint32_t>(js, "neighbours");
            surf.point_count = integer_at<std::uint32_t>(js, "points");
            surf.mean_residual = js.at("mean_residual").get<double>();
            surf.tolerance = js.value("tolerance", 0.0);
            surf.bounds.add(vec_of(js.at("bounds").at("min")) - r.meta.offset);
            surf.bounds.add(vec_of(js.at("bounds").at("max")) - r.meta.offset);
            if (!surf.normal.allFinite() || std::abs(surf.normal.norm() - 1.0) > 1e-6 ||
                !surf.home.allFinite())
                malformed(file, cat({"surface ", std::to_string(r.surfaces.size()),
                                     " has a bad normal or home point"}));
            r.surfaces.push_back(surf);
        }
        if (r.surfaces.size() != r.stats.surfaces)
            malformed(file,
                      cat({"summary says ", std::to_string(r.stats.surfaces), " surfaces but ",
                           std::to_string(r.surfaces.size()), " are listed"}));
    } catch (const nlohmann::json::exception& e) {
        malformed(file, cat({"missing or mistyped field: ", e.what()}));
    } catch (const std::invalid_argument& e) {
        malformed(file, e.what());
    }
    return r;
}

std::filesystem::path labels_file(const std::filesystem::path& dir) {
    std::error_code ec;
    const std::filesystem::path bin = dir / kLabelsFile, txt = dir / "labels.txt";
    if (!std::filesystem::exists(bin, ec) && std::filesystem::exists(txt, ec)) return txt;
    return bin;
}

std::vector<std::int32_t> read_labels(const std::filesystem::path& file) {
    if (file.extension() == ".txt") return read_labels_txt(file);
    const FileBytes bytes = FileBytes::read(file);
    return parse_labels_bin(bytes.view(), file.string());
}

std::vector<std::int32_t> parse_labels_bin(std::string_view bytes, std::string_view source) {
    const std::filesystem::path file(source);
    if (bytes.size() % sizeof(std::int32_t) != 0)
        malformed(file, cat({"is ", std::to_string(bytes.size()),
                             " bytes: not a whole number of 4-byte labels"}));
    std::vector<std::int32_t> labels(bytes.size() / sizeof(std::int32_t));
    if (!labels.empty()) std::memcpy(labels.data(), bytes.data(), bytes.size());
    for (std::size_t i = 0; i < labels.size(); ++i)
        if (labels[i] < -1)
            malformed(file, cat({"point ", std::to_string(i), " has label ",
                                 std::to_string(labels[i]), ": not a surface id (>= -1)"}));
    return labels;
}

std::vector<std::int32_t> read_labels_txt(const std::filesystem::path& file) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_labels_txt(bytes.view(), file.string());
}

std::vector<std::int32_t> parse_labels_txt(std::string_view text, std::string_view source) {
    const std::filesystem::path file(source);
    std::vector<std::int32_t> labels;
    const char* p = text.data();
    const char* end = p + text.size();
    std::size_t line = 1;
    while (p < end) {
        std::int32_t v = 0;
        const auto r = std::from_chars(p, end, v);
        if (r.ec != std::errc() || v < -1 || (r.ptr < end && *r.ptr != '\n'))
            malformed(file, cat({"line ", std::to_string(line),
                                 " is not a surface id (an integer >= -1)"}));
        labels.push_back(v);
        p = r.ptr < end ? r.ptr + 1 : r.ptr;
        ++line;
    }
    return labels;
}

}  // namespace surfgrow::io
