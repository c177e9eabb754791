#include "cli_common.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/length_limits.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow::cli {

namespace {

[[noreturn]] void usage_error(std::string_view option,
                              std::initializer_list<std::string_view> what) {
    std::string message = cat({option, ": "});
    for (auto w : what) message.append(w);
    throw Error(ErrorCode::kUsage, message);
}

[[noreturn]] void range_error(std::string_view option, std::string_view text,
                              std::string_view why) {
    throw Error(ErrorCode::kInvalidParameter, cat({option, ": ", trim(text), " ", why}));
}

// Splits "12.5mm" into the number and the unit text; false if there is no number. A number out
// of the double's range ("1e400m") or not finite ("nanm", "infm") is a number, but no length:
// refused here, naming the option.
bool split_number(std::string_view text, double& value, std::string_view& unit,
                  std::string_view option) {
    text = trim(text);
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec == std::errc::result_out_of_range)
        range_error(option, text, "is beyond the range of any length (a double)");
    if (ec != std::errc()) return false;
    if (!std::isfinite(value)) range_error(option, text, "is not a finite length");
    unit = trim(std::string_view(ptr, static_cast<std::size_t>(end - ptr)));
    return true;
}

// A length in metres checked against what float coordinates can express (length_limits.hpp).
double checked_length(double metres, std::string_view text, std::string_view option) {
    if (const std::string_view why = length_range_problem(metres); !why.empty())
        range_error(option, text, why);
    return metres;
}

constexpr std::array<std::pair<std::string_view, double>, 4> kLengthUnits{
    {{"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"um", 1e-6}}};

bool unit_scale(std::string_view unit, double& scale) {
    for (const auto& [name, s] : kLengthUnits) {
        if (unit == name) {
            scale = s;
            return true;
        }
    }
    return false;
}

}  // namespace

double parse_length_m(std::string_view text, std::string_view option) {
    double value = 0;
    std::string_view unit;
    if (!split_number(text, value, unit, option))
        usage_error(option, {"'", text, "' is not a length (expected e.g. 12mm or 0.012m)"});
    if (unit.empty())
        usage_error(option, {"'", text, "' has no unit; write e.g. ", trim(text), "mm or ",
                             trim(text), "m"});
    double scale = 1;
    if (!unit_scale(unit, scale))
        usage_error(option, {"unknown length unit '", unit, "' (use m, cm, mm)"});
    return checked_length(value * scale, text, option);
}

double parse_angle_deg(std::string_view text, std::string_view option) {
    double value = 0;
    std::string_view unit;
    if (!split_number(text, value, unit, option))
        usage_error(option, {"'", text, "' is not an angle (expected e.g. 0.5deg)"});
    // "a/b": a step like 1/3 deg is exact only as a fraction.
    if (!unit.empty() && unit.front() == '/') {
        double divisor = 0;
        std::string_view rest;
        if (!split_number(unit.substr(1), divisor, rest, option) || divisor == 0)
            usage_error(option, {"'", text, "' is not an angle (expected e.g. 1/3deg)"});
        value /= divisor;
        unit = rest;
    }
    if (unit.empty())
        usage_error(option, {"'", text, "' has no unit; write e.g. ", trim(text), "deg"});
    if (unit == "deg") return value;
    if (unit == "rad") return value * 180.0 / 3.14159265358979323846;
    usage_error(option, {"unknown angle unit '", unit, "' (use deg or rad)"});
}

std::chrono::milliseconds parse_duration(std::string_view text, std::string_view option,
                                         double min_ms, double max_ms) {
    double value = 0;
    std::string_view unit;
    if (!split_number(text, value, unit, option) || (unit != "ms" && unit != "s"))
        usage_error(option, {"'", text, "' is not a time (e.g. 500ms or 2s)"});
    const double ms = unit == "s" ? value * 1000 : value;
    if (!(ms >= min_ms && ms <= max_ms))
        range_error(option, text,
                    cat({"is not within ", std::to_string(static_cast<long long>(min_ms)),
                         " ms .. ", std::to_string(static_cast<long long>(max_ms / 1000)), " s"}));
    return std::chrono::milliseconds(static_cast<long long>(ms));
}

double unit_to_metres(std::string_view unit, std::string_view option) {
    double scale = 1;
    if (!unit_scale(trim(unit), scale))
        usage_error(option, {"unknown unit '", unit, "' (use m, cm or mm)"});
    return scale;
}

Vec3d parse_vec3(std::string_view text, std::string_view option) {
    Vec3d v;
    std::string_view rest = text;
    for (int i = 0; i < 3; ++i) {
        const auto comma = rest.find(',');
        const std::string_view part = trim(i < 2 ? rest.substr(0, comma) : rest);
        if ((i < 2 && comma == std::string_view::npos) || part.empty())
            usage_error(option, {"'", text, "' is not x,y,z"});
        double value = 0;
        auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (ec != std::errc() || ptr != part.data() + part.size() || !std::isfinite(value))
            usage_error(option, {"'", text, "' is not x,y,z (three numbers)"});
        v[i] = value;
        if (i < 2) rest.remove_prefix(comma + 1);
    }
    return v;
}

std::vector<double> parse_lengths_m(std::string_view text, std::string_view option,
                                    std::size_t count) {
    std::vector<std::string_view> parts;
    std::string_view rest = text;
    while (true) {
        const auto comma = rest.find(',');
        parts.push_back(trim(rest.substr(0, comma)));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
    }
    const std::string expected =
        std::to_string(count) + " comma-separated lengths (e.g. " +
        (count == 3 ? std::string("0,0,1.2m") : std::string("-1,-1,0,1,1,2m")) + ")";
    if (parts.size() != count) usage_error(option, {"'", text, "' is not ", expected});
    // A unit on the last component alone applies to every component without one ("1,2,0.5m").
    double last_scale = 0;
    {
        double value = 0;
        std::string_view unit;
        if (split_number(parts.back(), value, unit, option) && !unit.empty() &&
            !unit_scale(unit, last_scale))
            usage_error(option, {"unknown length unit '", unit, "' (use m, cm, mm)"});
    }
    std::vector<double> out;
    for (const std::string_view part : parts) {
        double value = 0;
        std::string_view unit;
        if (!split_number(part, value, unit, option))
            usage_error(option, {"'", text, "' is not ", expected});
        double scale = last_scale;
        if (!unit.empty() && !unit_scale(unit, scale))
            usage_error(option, {"unknown length unit '", unit, "' (use m, cm, mm)"});
        if (scale == 0) usage_error(option, {"'", text, "' has no unit; write e.g. ", text, "m"});
        out.push_back(checked_length(value * scale, part, option));
    }
    return out;
}

Vec3d parse_vec3_length_m(std::string_view text, std::string_view option) {
    const std::vector<double> v = parse_lengths_m(text, option, 3);
    return {v[0], v[1], v[2]};
}

std::string format_length(double metres) {
    char buf[64];
    const double a = std::abs(metres);
    if (a != 0 && a < 0.1)
        std::snprintf(buf, sizeof buf, "%g mm", metres * 1000);
    else
        std::snprintf(buf, sizeof buf, "%g m", metres);
    return buf;
}

std::string length_argument(double metres) {
    std::string s = format_length(metres);
    s.erase(std::remove(s.begin(), s.end(), ' '), s.end());
    return s;
}

bool stderr_is_terminal() {
    return ::isatty(STDERR_FILENO) == 1;
}

namespace {

// CLI11 transform: refuses a whole number that does not fit T (from_chars says so, or a minus
// sign before an unsigned one); passes everything else on unchanged.
template <typename T>
std::function<std::string(std::string)> fits(const std::string& option) {
    return [option](std::string text) {
        std::string_view digits = trim(text);
        if (digits.starts_with('+')) digits.remove_prefix(1);
        T value{};
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        const bool negative_unsigned =
            std::is_unsigned_v<T> && digits.starts_with('-') &&
            digits.find_first_not_of("-0123456789") == std::string_view::npos &&
            digits.find_first_not_of("-0") != std::string_view::npos;
        if (ec == std::errc::result_out_of_range || negative_unsigned)
            throw Error(ErrorCode::kInvalidParameter,
                        cat({option, ": ", trim(text), " is out of range (a whole number from ",
                             std::to_string(std::numeric_limits<T>::min()), " to ",
                             std::to_string(std::numeric_limits<T>::max()), ")"}));
        return text;
    };
}

}  // namespace

void add_seed_option(CLI::App& cmd, std::uint64_t& seed, const std::string& description) {
    cmd.add_option("--seed", seed, description)
        ->capture_default_str()
        ->transform(fits<std::uint64_t>("--seed"), "", "");
}

void add_count_option(CLI::App& cmd, const std::string& name, long long& count,
                      const std::string& description) {
    cmd.add_option(name, count, description)
        ->capture_default_str()
        ->transform(fits<long long>(name), "", "");
}

void add_threads_option(CLI::App& cmd, int& threads, const std::string& description) {
    cmd.add_option("--threads", threads, description)
        ->capture_default_str()
        ->transform(
            [](std::string text) {
                int n = 0;
                const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
                const int most = max_threads();
                // Only a whole number counts: "99999999999x" is left to CLI11, which refuses it
                // (found by fuzz/cli_args: it was clamped like a number beyond int).
                const bool whole = end == text.data() + text.size();
                const bool too_many = whole && (ec == std::errc::result_out_of_range ||
                                                (ec == std::errc() && n > most));
                // Negative counts are refused here, once for every command (0 = all cores).
                if (text.starts_with('-') && whole &&
                    ((ec == std::errc() && n < 0) || ec == std::errc::result_out_of_range))
                    throw Error(ErrorCode::kInvalidParameter,
                                cat({"--threads must be 0 (all cores) or more, got ", text}));
                if (!too_many) return text;
                std::fprintf(stderr,
                             "surfgrow: note: --threads %s is more than this machine can use; "
                             "using %d (%d per core)\n",
                             text.c_str(), most, kThreadsPerCore);
                return std::to_string(most);
            },
            "", "");
}

}  // namespace surfgrow::cli
