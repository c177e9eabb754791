#include "surfgrow/io/poses_file.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <ostream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io {

using nlohmann::json;
using scanner::Pose;

namespace {

constexpr std::size_t kMaxPosesFileBytes = 16u << 20;

// A pose from 16 (matrix, row-major) or 6 (x y z roll pitch yaw in degrees) numbers.
Pose pose_from_numbers(const std::vector<double>& v, std::string_view where) {
    try {
        if (v.size() == 16) {
            Eigen::Matrix4d m;
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) m(r, c) = v[static_cast<std::size_t>(4 * r + c)];
            return scanner::rigid_from_matrix(m);
        }
        if (v.size() == 6) {
            for (const double x : v)
                if (!std::isfinite(x))
                    throw Error(ErrorCode::kInvalidParameter,
                                "pose is not a rigid transform: it has a non-finite entry");
            return scanner::pose_from_xyz_rpy(
                Vec3d(v[0], v[1], v[2]), Vec3d(scanner::deg_to_rad(v[3]), scanner::deg_to_rad(v[4]),
                                               scanner::deg_to_rad(v[5])));
        }
    } catch (const Error& e) {
        detail::rethrow_in(where, e);
    }
    throw Error(
        ErrorCode::kMalformedInput,
        cat({where, ": a pose has 16 numbers (4x4 matrix) or 6 (x y z roll pitch yaw), got ",
             std::to_string(v.size())}));
}

std::vector<double> numbers_of(const json& arr, std::string_view where) {
    std::vector<double> v;
    for (const json& x : arr) {
        if (!x.is_number()) detail::malformed(where, "pose entries must be numbers");
        v.push_back(x.get<double>());
    }
    return v;
}

std::string line_where(std::string_view name, std::size_t line) {
    return cat({name, ":", std::to_string(line)});
}

}  // namespace

Pose pose_from_json(const json& j, std::string_view where) {
    if (j.is_array()) return pose_from_numbers(numbers_of(j, where), where);
    if (!j.is_object()) detail::malformed(where, "a pose is an array or an object");
    for (const auto& [key, value] : j.items()) {
        if (key != "matrix" && key != "position" && key != "rpy_deg")
            detail::malformed(where, cat({"unknown key '", key, "' in a pose"}));
        if (!value.is_array()) detail::malformed(where, cat({"'", key, "' must be an array"}));
    }
    if (j.contains("matrix")) {
        if (j.contains("position") || j.contains("rpy_deg"))
            detail::malformed(where, "a pose has either 'matrix' or 'position' and 'rpy_deg'");
        std::vector<double> v;
        for (const json& row : j.at("matrix")) {
            if (row.is_array()) {
                if (row.size() != 4) detail::malformed(where, "each matrix row has 4 numbers");
                for (const double x : numbers_of(row, where)) v.push_back(x);
            } else {
                if (!row.is_number()) detail::malformed(where, "matrix entries must be numbers");
                v.push_back(row.get<double>());
            }
        }
        if (v.size() != 16) detail::malformed(where, "'matrix' needs 4 rows of 4 numbers");
        return pose_from_numbers(v, where);
    }
    if (!j.contains("position") || !j.contains("rpy_deg"))
        detail::malformed(where, "a pose object needs 'matrix', or 'position' and 'rpy_deg'");
    const auto p = numbers_of(j.at("position"), where), a = numbers_of(j.at("rpy_deg"), where);
    if (p.size() != 3 || a.size() != 3)
        detail::malformed(where, "'position' and 'rpy_deg' have 3 numbers each");
    return pose_from_numbers({p[0], p[1], p[2], a[0], a[1], a[2]}, where);
}

json pose_to_json(const Pose& pose) {
    json rows = json::array();
    for (int r = 0; r < 4; ++r) {
        json row = json::array();
        for (int c = 0; c < 4; ++c) row.push_back(pose.matrix()(r, c));
        rows.push_back(row);
    }
    return json{{"matrix", rows}};
}

std::vector<Pose> parse_poses_text(std::string_view text, std::string_view name) {
    std::vector<Pose> poses;
    std::size_t line_no = 0;
    while (!text.empty()) {
        ++line_no;
        const std::size_t eol = text.find('\n');
        std::string_view line = text.substr(0, eol);
        text = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
        if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        std::vector<double> v;
        std::size_t i = 0;
        while (i < line.size()) {
            const char c = line[i];
            if (c == ' ' || c == '\t' || c == ',' || c == '\r') {
                ++i;
                continue;
            }
            std::size_t end = i;
            while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != ',' &&
                   line[end] != '\r')
                ++end;
            const std::string_view token = line.substr(i, end - i);
            double x = 0.0;
            const char* first = token.data();
            if (token.front() == '+') ++first;  // from_chars rejects a leading '+'
            const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), x);
            if (ec != std::errc() || ptr != token.data() + token.size())
                detail::malformed(line_where(name, line_no),
                                  cat({"'", token, "' is not a number"}));
            v.push_back(x);
            i = end;
        }
        if (v.empty()) continue;
        poses.push_back(pose_from_numbers(v, line_where(name, line_no)));
    }
    if (poses.empty()) detail::malformed(name, "no pose in the file");
    return poses;
}

std::vector<Pose> parse_poses_json(std::string_view text, std::string_view name) {
    detail::check_json_limits(text, name);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        detail::malformed(name, cat({"invalid JSON: ", e.what()}));
    }
    const json* list = &doc;
    if (doc.is_object()) {
        for (const auto& [key, value] : doc.items())
            if (key != "poses") detail::malformed(name, cat({"unknown key '", key, "'"}));
        if (!doc.contains("poses")) detail::malformed(name, "missing 'poses'");
        list = &doc.at("poses");
    }
    if (!list->is_array()) detail::malformed(name, "'poses' must be an array");
    std::vector<Pose> poses;
    for (std::size_t k = 0; k < list->size(); ++k)
        poses.push_back(pose_from_json((*list)[k], cat({name, ": pose ", std::to_string(k)})));
    if (poses.empty()) detail::malformed(name, "no pose in the file");
    return poses;
}

std::vector<Pose> read_poses_file(const std::filesystem::path& path) {
    const std::string text = detail::read_file_capped(path, kMaxPosesFileBytes, "a poses file");
    return parse_poses_file(text, path.string());
}

std::vector<Pose> parse_poses_file(std::string_view text, std::string_view name) {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string_view::npos && (text[first] == '{' || text[first] == '['))
        return parse_poses_json(text, name);
    return parse_poses_text(text, name);
}

std::string poses_to_text(const std::vector<Pose>& poses) {
    std::string out = "# surfgrow scan poses: one sensor-to-world 4x4 matrix per line, row-major\n";
    for (const Pose& p : poses) {
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                out += num(p.matrix()(r, c));
                out += (r == 3 && c == 3) ? '\n' : ' ';
            }
    }
    return out;
}

void write_poses_file(const std::filesystem::path& path, const std::vector<Pose>& poses) {
    const std::string text = poses_to_text(poses);
    write_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace surfgrow::io
