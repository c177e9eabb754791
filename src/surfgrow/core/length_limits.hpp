// The lengths a cloud of float coordinates can express. Every length parameter, on the command
// line and in the library's configurations, is checked against them: beyond them the arithmetic
// overflows (a radius squared, one over a band width) instead of giving a wrong-but-finite answer.
#pragma once

#include <cfloat>
#include <cmath>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

/// Largest length: no two float coordinates lie farther apart than FLT_MAX in any one axis.
inline constexpr double kMaxLength = FLT_MAX;
/// Smallest length but 0: float coordinates cannot resolve less, and 1 / it would overflow a float.
inline constexpr double kMinLength = FLT_MIN;

/// Why `value` is no length a float cloud can express, or "" when it is one (0, or a magnitude
/// within [kMinLength, kMaxLength]). Signs are left to each parameter's own rule.
[[nodiscard]] inline std::string_view length_range_problem(double value) {
    if (!std::isfinite(value)) return "is not a finite length";
    const double a = std::abs(value);
    if (a > kMaxLength) return "is beyond the range of float coordinates (at most 3.4e+38)";
    if (a != 0 && a < kMinLength)
        return "is below the smallest length float coordinates resolve (1.2e-38)";
    return {};
}

/// Throws Error(kInvalidParameter) "NAME = VALUE is ..." unless `value` passes
/// length_range_problem.
inline void check_length_range(std::string_view name, double value) {
    if (const std::string_view why = length_range_problem(value); !why.empty())
        throw Error(ErrorCode::kInvalidParameter, cat({name, " = ", num(value), " ", why}));
}

}  // namespace surfgrow
