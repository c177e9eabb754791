// Field checks shared by the JSON readers of planes.json and coverage.json.
#pragma once

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io::json_fields {

using nlohmann::json;
using nlohmann::ordered_json;

/// [x, y, z] for writing.
inline ordered_json vec_json(const Vec3d& v) {
    return ordered_json::array({v.x(), v.y(), v.z()});
}

/// Throws Error(kMalformedInput, "<file>: <what>").
[[noreturn]] inline void malformed(const std::filesystem::path& file, std::string_view what) {
    throw Error(ErrorCode::kMalformedInput, cat({file.string(), ": ", what}));
}

/// JSON `text` parsed; `file` names it in messages. Throws Error(kMalformedInput) when it is not
/// JSON or nests deeper than detail::check_json_limits allows (no memory blow-up on "[[[[...").
inline json parse_text(std::string_view text, const std::filesystem::path& file) {
    detail::check_json_limits(text, file.string());
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        malformed(file, cat({"not valid JSON: ", e.what()}));
    }
}

// The checks below throw std::invalid_argument naming the field; the readers add file and place.

inline std::string string_of(const json& j, const char* what) {
    if (!j.is_string()) throw std::invalid_argument(cat({what, " is not a string"}));
    return j.get_ref<const std::string&>();
}

inline Vec3d vec_of(const json& j, const char* what) {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number())
        throw std::invalid_argument(cat({what, " is not [x, y, z]"}));
    const Vec3d v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
    if (!v.allFinite()) throw std::invalid_argument(cat({what, " is not finite"}));
    return v;
}

inline void check_unit(const Vec3d& v, const char* what) {
    if (std::abs(v.norm() - 1.0) > 1e-6)
        throw std::invalid_argument(cat({what, " is not a unit vector"}));
}

inline Vec3d unit_of(const json& j, const char* what) {
    const Vec3d v = vec_of(j, what);
    check_unit(v, what);
    return v;
}

inline double non_negative(const json& j, const char* what) {
    if (!j.is_number()) throw std::invalid_argument(cat({what, " is not a number"}));
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < 0) throw std::invalid_argument(cat({what, " must be >= 0"}));
    return v;
}

}  // namespace surfgrow::io::json_fields
