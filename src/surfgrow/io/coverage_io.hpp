// coverage.json and coverage.csv: goals, approach poses and the path, for robot programs.
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "surfgrow/io/results_io.hpp"
#include "surfgrow/robot/coverage.hpp"

namespace surfgrow::io {

/// coverage.json: parameters (resolved), summary (goals, coverage, path lengths, transitions),
/// per plane (visiting order) and every goal in path order with its pose. Positions in file
/// coordinates (meta.offset added). Deterministic.
void write_coverage_json(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta);

/// coverage.csv: one row per goal in path order, the columns of kCoverageCsvHeader.
void write_coverage_csv(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta);

/// The header row of coverage.csv.
inline constexpr const char* kCoverageCsvHeader =
    "seq,plane,row,x,y,z,nx,ny,nz,tool_x,tool_y,tool_z,axis_x,axis_y,axis_z,qw,qx,qy,qz,"
    "tilt_deg,transition,from_home";

/// A plan read back, positions relative to meta.offset.
struct StoredCoverage {
    CoveragePlan plan;
    ResultMeta meta;
};

/// Reads coverage.json. Throws Error(kCannotOpen) or Error(kMalformedInput) naming the file and
/// the goal (another format, a vector that is not 3 finite numbers, a non-unit axis or
/// quaternion, counts that do not match).
[[nodiscard]] StoredCoverage read_coverage_json(const std::filesystem::path& file);
/// The same for coverage.json held in memory; `source` names it in messages.
[[nodiscard]] StoredCoverage parse_coverage_json(std::string_view text, std::string_view source);

/// Reads coverage.csv: goals in file order, positions relative to `offset`. Throws
/// Error(kCannotOpen) or Error(kMalformedInput) naming the file and line (a wrong header, a row
/// with the wrong number of fields, a field that is not a number, a non-unit axis).
[[nodiscard]] std::vector<CoverageGoal> read_coverage_csv(const std::filesystem::path& file,
                                                          const Vec3d& offset = Vec3d::Zero());
/// The same for coverage.csv held in memory; `source` names it in messages.
[[nodiscard]] std::vector<CoverageGoal> parse_coverage_csv(std::string_view text,
                                                           std::string_view source,
                                                           const Vec3d& offset = Vec3d::Zero());

}  // namespace surfgrow::io
