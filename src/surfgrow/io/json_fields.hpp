// Field checks shared by the JSON readers (planes.json, coverage.json, surfaces.json, ...).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

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

/// A count, id or version: a JSON integer within T's range. A float (1e20), a negative for an
/// unsigned T or a larger number is refused: nlohmann's get<T>() would convert it with undefined
/// behaviour or wrap it (found by fuzz/planes_json and fuzz/surfaces_json).
template <class T>
T integer_of(const json& j, const char* what) {
    static_assert(std::is_integral_v<T>);
    using Limits = std::numeric_limits<T>;
    const auto refuse = [&] {
        return std::invalid_argument(
            cat({what, " must be a whole number from ", std::to_string(Limits::min()), " to ",
                 std::to_string(Limits::max())}));
    };
    if (j.is_number_unsigned()) {  // nlohmann parses every integer >= 0 as unsigned
        const auto v = j.get<std::uint64_t>();
        if (v > static_cast<std::uint64_t>(Limits::max())) throw refuse();
        return static_cast<T>(v);
    }
    if (j.is_number_integer()) {  // negative
        const auto v = j.get<std::int64_t>();
        if constexpr (std::is_unsigned_v<T>) {
            throw refuse();
        } else {
            if (v < static_cast<std::int64_t>(Limits::min())) throw refuse();
            return static_cast<T>(v);
        }
    }
    throw refuse();
}

/// integer_of of an object's field, named by its key.
template <class T>
T integer_at(const json& object, const char* key) {
    return integer_of<T>(object.at(key), key);
}

inline double non_negative(const json& j, const char* what) {
    if (!j.is_number()) throw std::invalid_argument(cat({what, " is not a number"}));
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < 0) throw std::invalid_argument(cat({what, " must be >= 0"}));
    return v;
}

}  // namespace surfgrow::io::json_fields
