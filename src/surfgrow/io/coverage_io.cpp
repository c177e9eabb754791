#include "surfgrow/io/coverage_io.hpp"

#include <bit>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/file_bytes.hpp"
#include "surfgrow/io/fixed_ply_header.hpp"
#include "surfgrow/io/json_fields.hpp"
#include "surfgrow/io/output_buffer.hpp"

namespace surfgrow::io {

namespace {

using namespace json_fields;

Eigen::Quaterniond quaternion_of(double w, double x, double y, double z) {
    const Eigen::Quaterniond q(w, x, y, z);
    if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1.0) > 1e-6)
        throw std::invalid_argument("its orientation is not a unit quaternion");
    return q;
}

static_assert(std::endian::native == std::endian::little,
              "coverage.ply is written and read on little-endian hosts only");

// coverage.ply's vertex properties, "TYPE NAME" in file order: the writer's header and what
// the reader expects. Positions in double when `wide` (georeferenced).
std::vector<std::string> goal_layout(bool wide) {
    const std::string pos = wide ? "double " : "float ";
    std::vector<std::string> layout;
    for (const char* name : {"x", "y", "z"}) layout.push_back(pos + name);
    for (const char* name : {"nx", "ny", "nz", "dx", "dy", "dz"})
        layout.push_back(cat({"float ", name}));
    for (const char* name : {"tool_x", "tool_y", "tool_z"}) layout.push_back(pos + name);
    for (const char* name : {"axis_x", "axis_y", "axis_z", "qw", "qx", "qy", "qz", "tilt_deg"})
        layout.push_back(cat({"float ", name}));
    for (const char* p : {"uint plane", "uint row", "uchar transition", "uchar from_home"})
        layout.emplace_back(p);
    return layout;
}

}  // namespace

void write_coverage_json(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta) {
    const CoverageConfig& c = plan.config;
    const CoverageStats& s = plan.stats;
    ordered_json doc = {
        {"format", "surfgrow-coverage"},
        {"version", 2},
        {"units", meta.units},
        {"offset", vec_json(meta.offset)},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"parameters",
         {{"blast_radius", c.blast_radius},
          {"standoff", c.standoff},
          {"angle_band_deg", {c.min_angle_deg, c.max_angle_deg}},
          {"tilt_deg", c.tilt_deg.value_or(c.min_angle_deg)},
          {"sample_spacing", c.sample_spacing},
          {"start", c.start ? vec_json(*c.start + meta.offset) : ordered_json(nullptr)}}},
        {"summary",
         {{"goals", s.goals},
          {"planes", s.planes},
          {"transitions", s.transitions},
          {"area", s.area},
          {"covered_area", s.covered_area},
          {"coverage", s.coverage},
          {"tool_path_length", s.tool_path_length},
          {"sweep_length", s.sweep_length},
          {"transition_length", s.transition_length},
          {"goal_path_length", s.goal_path_length}}},
    };
    doc["goals_file"] = kCoverageGoalsFile;
    // The head indented, then one line per plane.
    std::string text = doc.dump(1);
    text.pop_back();  // the closing brace
    while (!text.empty() && text.back() == '\n') text.pop_back();
    text += ",\n \"planes\": [";
    for (std::size_t k = 0; k < plan.per_plane.size(); ++k) {
        const PlaneCoverage& p = plan.per_plane[k];
        const ordered_json row = {{"plane", p.plane},
                                  {"goals", p.goals},
                                  {"first_goal", p.first_goal},
                                  {"area", p.area},
                                  {"covered_fraction", p.covered_fraction}};
        text += k ? ",\n  " : "\n  ";
        text += row.dump();
    }
    text += plan.per_plane.empty() ? "]\n}\n" : "\n ]\n}\n";
    out << text;
}

void write_coverage_ply(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta) {
    const bool wide = meta.offset != Vec3d::Zero();  // keep georeferenced precision
    const std::vector<std::string> layout = goal_layout(wide);
    const std::string head =
        fixed_ply_head("surfgrow coverage goals: one vertex per goal in path order", meta.units,
                       meta.result_id, plan.goals.size(), layout);
    std::string body(plan.goals.size() * record_bytes(layout), '\0');
    char* at = body.data();
    auto put = [&at](auto v) {
        std::memcpy(at, &v, sizeof v);
        at += sizeof v;
    };
    auto put_position = [&](const Vec3d& v) {
        for (int a = 0; a < 3; ++a) {
            if (wide)
                put(v[a]);
            else
                put(static_cast<float>(v[a]));
        }
    };
    auto put_floats = [&](const auto& v, int n) {
        for (int a = 0; a < n; ++a) put(static_cast<float>(v[a]));
    };
    for (const CoverageGoal& g : plan.goals) {
        put_position(g.position + meta.offset);
        put_floats(g.normal, 3);
        put_floats(g.direction, 3);
        put_position(g.tool_position + meta.offset);
        put_floats(g.tool_axis, 3);
        const Eigen::Quaterniond& q = g.orientation;
        put_floats(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 4);
        put(static_cast<float>(g.tilt_deg));
        put(g.plane);
        put(g.row);
        put(static_cast<std::uint8_t>(g.transition));
        put(static_cast<std::uint8_t>(g.from_home));
    }
    assert(at == body.data() + body.size());
    out << head << body;
}

void write_coverage_csv(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta) {
    OutputBuffer buf(out);
    buf.append(kCoverageCsvHeader);
    buf.put('\n');
    for (std::size_t k = 0; k < plan.goals.size(); ++k) {
        const CoverageGoal& g = plan.goals[k];
        buf.put_number(k);
        buf.put(',');
        buf.put_number(g.plane);
        buf.put(',');
        buf.put_number(g.row);
        auto field = [&](double v) {
            buf.put(',');
            buf.put_number(v);
        };
        for (int a = 0; a < 3; ++a) field(g.position[a] + meta.offset[a]);
        for (int a = 0; a < 3; ++a) field(g.normal[a]);
        for (int a = 0; a < 3; ++a) field(g.tool_position[a] + meta.offset[a]);
        for (int a = 0; a < 3; ++a) field(g.tool_axis[a]);
        field(g.orientation.w());
        field(g.orientation.x());
        field(g.orientation.y());
        field(g.orientation.z());
        field(g.tilt_deg);
        buf.append(g.transition ? ",1" : ",0");
        buf.append(g.from_home ? ",1\n" : ",0\n");
    }
    buf.flush();
}

StoredCoverage read_coverage_json(const std::filesystem::path& file) {
    const FileBytes bytes = FileBytes::read(file);
    StoredCoverage r = parse_coverage_json(bytes.view(), file.string());
    if (r.goals_file.empty()) return r;  // version 1: goals inline
    const std::filesystem::path goals_path = file.parent_path() / r.goals_file;
    StoredGoals g = read_coverage_ply(goals_path, r.meta.offset);
    if (g.goals.size() != r.plan.stats.goals)
        malformed(goals_path,
                  cat({"holds ", std::to_string(g.goals.size()), " goals but ",
                       file.filename().string(), " says ", std::to_string(r.plan.stats.goals)}));
    if (g.result_id != r.meta.result_id)
        malformed(goals_path, cat({"belongs to another plan (result_id \"", g.result_id, "\", ",
                                   file.filename().string(), " has \"", r.meta.result_id,
                                   "\"): run `surfgrow coverage` again"}));
    r.plan.goals = std::move(g.goals);
    return r;
}

StoredGoals read_coverage_ply(const std::filesystem::path& file, const Vec3d& offset) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_coverage_ply(bytes.view(), file.string(), offset);
}

StoredGoals parse_coverage_ply(std::string_view all, std::string_view source, const Vec3d& offset) {
    const std::filesystem::path file(source);
    const FixedPlyHeader h = read_fixed_ply_header(all, source);
    const bool wide = h.positions_in_double();
    const std::vector<std::string> layout = goal_layout(wide);
    if (!h.is_vertex_layout(layout))
        malformed(file,
                  "not a surfgrow coverage goals file (expected the layout coverage.ply is "
                  "written in)");
    const std::uint64_t count = h.elements[0].second;
    const std::size_t size = record_bytes(layout);
    const std::size_t body = h.body;
    if (count > all.size() / size || all.size() - body != count * size)
        malformed(file, cat({"truncated or too long: the header promises ", std::to_string(count),
                             " goals"}));
    StoredGoals r;
    r.result_id = h.result_id;
    const char* p = all.data() + body;
    auto take = [&p](auto& v) {
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
    };
    auto position = [&] {
        Vec3d v;
        for (int a = 0; a < 3; ++a) {
            if (wide) {
                take(v[a]);
            } else {
                float x;
                take(x);
                v[a] = x;
            }
        }
        return v;
    };
    auto floats = [&](int n) {
        Eigen::Vector4d v = Eigen::Vector4d::Zero();
        for (int a = 0; a < n; ++a) {
            float x;
            take(x);
            v[a] = x;
        }
        return v;
    };
    // Stored as float: a unit vector comes back within float rounding of unit, and is made
    // unit again.
    auto unit = [&](const Eigen::Vector4d& v, int n, const char* what, std::size_t k) {
        const double norm = v.head(n).norm();
        if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-5)
            malformed(file,
                      cat({"goal ", std::to_string(k), ": its ", what, " is not a unit vector"}));
        return Eigen::Vector4d(v / norm);
    };
    r.goals.resize(static_cast<std::size_t>(count));
    for (std::size_t k = 0; k < r.goals.size(); ++k) {
        CoverageGoal& g = r.goals[k];
        g.position = position() - offset;
        g.normal = unit(floats(3), 3, "normal", k).head<3>();
        g.direction = unit(floats(3), 3, "direction", k).head<3>();
        g.tool_position = position() - offset;
        g.tool_axis = unit(floats(3), 3, "tool axis", k).head<3>();
        const Eigen::Vector4d q = unit(floats(4), 4, "orientation", k);
        g.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
        float tilt;
        take(tilt);
        g.tilt_deg = tilt;
        take(g.plane);
        take(g.row);
        std::uint8_t transition, from_home;
        take(transition);
        take(from_home);
        g.transition = transition != 0;
        g.from_home = from_home != 0;
        if (!g.position.allFinite() || !g.tool_position.allFinite() || !std::isfinite(g.tilt_deg))
            malformed(file, cat({"goal ", std::to_string(k), " is not finite"}));
    }
    return r;
}

StoredCoverage parse_coverage_json(std::string_view text, std::string_view source) {
    const std::filesystem::path file(source);
    const json j = parse_text(text, file);
    StoredCoverage r;
    CoveragePlan& plan = r.plan;
    std::string where = "the header";
    try {
        if (!j.is_object() || j.value("format", "") != "surfgrow-coverage")
            malformed(file, "not a surfgrow coverage file (no \"format\": \"surfgrow-coverage\")");
        const int version = integer_at<int>(j, "version");
        if (version != 1 && version != 2)
            malformed(file, "only versions 1 and 2 are supported (a newer surfgrow wrote it?)");
        r.meta.units = string_of(j.at("units"), "units");
        r.meta.offset = vec_of(j.at("offset"), "offset");
        r.meta.input = j.contains("input") ? string_of(j.at("input"), "input") : std::string();
        r.meta.result_id =
            j.contains("result_id") ? string_of(j.at("result_id"), "result_id") : std::string();
        const json& p = j.at("parameters");
        CoverageConfig& c = plan.config;
        c.blast_radius = p.at("blast_radius").get<double>();
        c.standoff = p.at("standoff").get<double>();
        const json& band = p.at("angle_band_deg");
        if (!band.is_array() || band.size() != 2)
            throw std::invalid_argument("angle_band_deg is not [min, max]");
        c.min_angle_deg = band[0].get<double>();
        c.max_angle_deg = band[1].get<double>();
        c.tilt_deg = p.at("tilt_deg").get<double>();
        c.sample_spacing = p.at("sample_spacing").get<double>();
        if (!p.at("start").is_null()) c.start = vec_of(p.at("start"), "start") - r.meta.offset;
        validate(c);
        const json& s = j.at("summary");
        CoverageStats& st = plan.stats;
        st.goals = integer_at<std::uint64_t>(s, "goals");
        st.planes = integer_at<std::uint64_t>(s, "planes");
        st.transitions = integer_at<std::uint64_t>(s, "transitions");
        st.area = s.at("area").get<double>();
        st.covered_area = s.at("covered_area").get<double>();
        st.coverage = s.at("coverage").get<double>();
        st.tool_path_length = s.at("tool_path_length").get<double>();
        st.sweep_length = s.at("sweep_length").get<double>();
        st.transition_length = s.at("transition_length").get<double>();
        st.goal_path_length = s.at("goal_path_length").get<double>();
        for (const json& jp : j.at("planes"))
            plan.per_plane.push_back(
                {integer_at<std::uint32_t>(jp, "plane"), integer_at<std::uint32_t>(jp, "goals"),
                 integer_at<std::uint32_t>(jp, "first_goal"), jp.at("area").get<double>(),
                 jp.at("covered_fraction").get<double>()});
        if (version == 2) {  // the goals are in the file it names, beside it
            r.goals_file = string_of(j.at("goals_file"), "goals_file");
            if (r.goals_file.empty() || r.goals_file == "." || r.goals_file == ".." ||
                r.goals_file.find_first_of("/\\") != std::string::npos)
                throw std::invalid_argument("goals_file is not the name of a file beside it");
            return r;
        }
        const json& goals = j.at("goals");
        if (!goals.is_array() || goals.size() != st.goals)
            throw std::invalid_argument(cat({"the summary says ", std::to_string(st.goals),
                                             " goals but the list does not hold that many"}));
        for (std::size_t k = 0; k < goals.size(); ++k) {
            where = cat({"goal ", std::to_string(k)});
            const json& jg = goals[k];
            CoverageGoal g;
            g.plane = integer_at<std::uint32_t>(jg, "plane");
            g.row = integer_at<std::uint32_t>(jg, "row");
            g.position = vec_of(jg.at("position"), "its position") - r.meta.offset;
            g.normal = vec_of(jg.at("normal"), "its normal");
            g.direction = vec_of(jg.at("direction"), "its direction");
            g.tool_position = vec_of(jg.at("tool_position"), "its tool position") - r.meta.offset;
            g.tool_axis = vec_of(jg.at("tool_axis"), "its tool axis");
            check_unit(g.normal, "its normal");
            check_unit(g.tool_axis, "its tool axis");
            const json& q = jg.at("orientation");
            if (!q.is_array() || q.size() != 4)
                throw std::invalid_argument("its orientation is not [w, x, y, z]");
            g.orientation = quaternion_of(q[0].get<double>(), q[1].get<double>(),
                                          q[2].get<double>(), q[3].get<double>());
            g.tilt_deg = jg.at("tilt_deg").get<double>();
            g.from_home = jg.at("from_home").get<bool>();
            g.transition = jg.at("transition").get<bool>();
            plan.goals.push_back(g);
        }
    } catch (const json::exception& e) {
        malformed(file, cat({where, ": missing or mistyped field: ", e.what()}));
    } catch (const std::invalid_argument& e) {
        malformed(file, cat({where, ": ", e.what()}));
    } catch (const Error& e) {
        malformed(file, cat({where, ": ", e.what()}));
    }
    return r;
}

std::vector<CoverageGoal> read_coverage_csv(const std::filesystem::path& file,
                                            const Vec3d& offset) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_coverage_csv(bytes.view(), file.string(), offset);
}

std::vector<CoverageGoal> parse_coverage_csv(std::string_view text, std::string_view source,
                                             const Vec3d& offset) {
    const std::filesystem::path file(source);
    std::vector<CoverageGoal> goals;
    std::size_t line_no = 0;
    auto next_line = [&](std::string_view& line) {
        if (text.empty()) return false;
        const std::size_t nl = text.find('\n');
        line = text.substr(0, nl);
        text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        ++line_no;
        return true;
    };
    auto bad = [&](std::string_view what) {
        malformed(file, cat({"line ", std::to_string(line_no), ": ", what}));
    };
    std::string_view line;
    if (!next_line(line) || line != kCoverageCsvHeader)
        malformed(file, cat({"line 1 is not the coverage.csv header (", kCoverageCsvHeader, ")"}));
    constexpr std::size_t kFields = 22;
    double f[kFields];
    while (next_line(line)) {
        if (line.empty()) continue;
        std::size_t n = 0;
        std::string_view rest = line;
        while (true) {
            const std::size_t comma = rest.find(',');
            const std::string_view field = rest.substr(0, comma);
            if (n == kFields) bad(cat({"more than ", std::to_string(kFields), " fields"}));
            const auto r = std::from_chars(field.data(), field.data() + field.size(), f[n]);
            if (r.ec != std::errc() || r.ptr != field.data() + field.size() || !std::isfinite(f[n]))
                bad(cat({"field ", std::to_string(n + 1), " is not a finite number"}));
            ++n;
            if (comma == std::string_view::npos) break;
            rest.remove_prefix(comma + 1);
        }
        if (n != kFields)
            bad(cat({std::to_string(n), " fields where ", std::to_string(kFields), " are needed"}));
        constexpr double kMaxId = std::numeric_limits<std::uint32_t>::max();
        if (f[1] < 0 || f[2] < 0 || f[1] != std::floor(f[1]) || f[2] != std::floor(f[2]) ||
            f[1] > kMaxId || f[2] > kMaxId)
            bad("plane and row must be whole numbers from 0 to 2^32 - 1");
        CoverageGoal g;
        g.plane = static_cast<std::uint32_t>(f[1]);
        g.row = static_cast<std::uint32_t>(f[2]);
        g.position = Vec3d(f[3], f[4], f[5]) - offset;
        g.normal = Vec3d(f[6], f[7], f[8]);
        g.tool_position = Vec3d(f[9], f[10], f[11]) - offset;
        g.tool_axis = Vec3d(f[12], f[13], f[14]);
        try {
            check_unit(g.normal, "the normal");
            check_unit(g.tool_axis, "the tool axis");
            g.orientation = quaternion_of(f[15], f[16], f[17], f[18]);
        } catch (const std::invalid_argument& e) {
            bad(e.what());
        }
        g.tilt_deg = f[19];
        g.transition = f[20] != 0;
        g.from_home = f[21] != 0;
        goals.push_back(g);
    }
    return goals;
}

}  // namespace surfgrow::io
