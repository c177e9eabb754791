// Parsing and formatting shared by the subcommands: lengths with units, vectors, progress.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/core/geometry.hpp"

namespace CLI {
class App;
}

namespace surfgrow::cli {

/// The --threads option every subcommand has (0 = all cores, negative refused); a request above
/// what the machine can use (surfgrow::max_threads()) is clamped with a note on stderr.
void add_threads_option(CLI::App& cmd, int& threads, const std::string& description);

/// A whole-number option of type T (a seed, a count) whose value must fit T: CLI11 alone saturates
/// 2^64 to 2^64 - 1 and wraps -1 to 2^64 - 1 for a 64-bit option. Out of range is
/// Error(kInvalidParameter) naming the option; anything else is left to CLI11's conversion.
void add_seed_option(CLI::App& cmd, std::uint64_t& seed, const std::string& description);
void add_count_option(CLI::App& cmd, const std::string& name, long long& count,
                      const std::string& description);

/// Parses a length with its unit ("12mm", "1.2 cm", "0.012m", "1e-2m") into metres.
/// A bare number is refused: in a tool that mixes metre and millimetre clouds, a silent
/// factor of 1000 is worse than a short error. Throws Error(kUsage) naming `option`.
double parse_length_m(std::string_view text, std::string_view option);

/// Parses an angle with its unit ("0.5deg", "1/3deg", "0.01rad") into degrees. A bare number
/// is refused, as for lengths. Throws Error(kUsage) naming `option`; Error(kInvalidParameter)
/// for a number beyond a double or not finite.
double parse_angle_deg(std::string_view text, std::string_view option);

/// Parses a time with its unit ("500ms", "2s") into milliseconds, within [min_ms, max_ms].
/// Throws Error(kUsage) for no time, Error(kInvalidParameter) beyond the bounds, naming `option`.
std::chrono::milliseconds parse_duration(std::string_view text, std::string_view option,
                                         double min_ms, double max_ms);

/// Metres per unit of a cloud: "m" -> 1, "cm" -> 0.01, "mm" -> 0.001. Throws Error(kUsage).
double unit_to_metres(std::string_view unit, std::string_view option);

/// Parses "x,y,z" (three numbers, in the cloud's units). Throws Error(kUsage) naming `option`.
Vec3d parse_vec3(std::string_view text, std::string_view option);

/// Parses "x,y,z" where each number may carry a length unit ("1m,2m,0.5m" or "1,2,0.5m"
/// with the unit on the last); returns metres. A vector with no unit at all is refused.
Vec3d parse_vec3_length_m(std::string_view text, std::string_view option);

/// Parses `count` comma-separated lengths ("-1,-1,0,1,1,2m": a unit on the last applies to all
/// without their own); returns metres. Throws Error(kUsage) naming `option`.
std::vector<double> parse_lengths_m(std::string_view text, std::string_view option,
                                    std::size_t count);

/// "12 mm", "1.5 m": a length in metres shown in the unit a person would use.
std::string format_length(double metres);

/// A length as a command-line argument ("48mm", "1.5m"), for advice the user can paste.
std::string length_argument(double metres);

/// True when stderr is a terminal (progress is shown only then).
bool stderr_is_terminal();

}  // namespace surfgrow::cli
