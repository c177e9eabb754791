// coverage.json, coverage.ply and coverage.csv: goals, approach poses and the path, for robot
// programs. The JSON holds the parameters and summary; the goals are binary (coverage.ply).
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "surfgrow/io/results_io.hpp"
#include "surfgrow/robot/coverage.hpp"

namespace surfgrow::io {

/// Where coverage.json (version 2) says its goals are, beside it.
inline constexpr const char* kCoverageGoalsFile = "coverage.ply";

/// coverage.json (version 2): parameters (resolved), summary (goals, coverage, path lengths,
/// transitions) and per plane (visiting order); the goals themselves are in coverage.ply
/// ("goals_file"). Positions in file coordinates (meta.offset added). Deterministic.
void write_coverage_json(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta);

/// coverage.ply: one vertex per goal in path order, binary little-endian: x, y, z (the goal on
/// the plane), nx, ny, nz (the plane's normal), so Open3D and numpy read it as a point cloud
/// with normals; then dx, dy, dz (sweep direction), tool_x, tool_y, tool_z, axis_x, axis_y,
/// axis_z, qw, qx, qy, qz, tilt_deg, plane, row, transition, from_home. Positions in double
/// when meta.offset is non-zero (georeferenced), float otherwise; result_id in a comment.
void write_coverage_ply(std::ostream& out, const CoveragePlan& plan, const ResultMeta& meta);

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
    /// Version 2: the file beside it that holds the goals (plan.goals is then filled by
    /// read_coverage_json, left empty by parse_coverage_json). Empty for version 1, whose goals
    /// are inline.
    std::string goals_file;
};

/// Reads coverage.json, and for version 2 its goals from the coverage.ply beside it, which must
/// hold as many goals as the summary says and carry the same result_id. Throws
/// Error(kCannotOpen) or Error(kMalformedInput) naming the file and the goal (another format, a
/// vector that is not 3 finite numbers, a non-unit axis or quaternion, counts or ids that do
/// not match).
[[nodiscard]] StoredCoverage read_coverage_json(const std::filesystem::path& file);
/// The same for coverage.json held in memory, without reading any other file; `source` names
/// it in messages.
[[nodiscard]] StoredCoverage parse_coverage_json(std::string_view text, std::string_view source);

/// Goals read back from coverage.ply, positions relative to `offset`, and the file's result_id.
struct StoredGoals {
    std::vector<CoverageGoal> goals;
    std::string result_id;
};
/// Reads coverage.ply as write_coverage_ply writes it. Throws Error(kCannotOpen) or
/// Error(kMalformedInput) naming the file and the problem (another layout, truncated, a value
/// that is not finite, a non-unit vector or quaternion).
[[nodiscard]] StoredGoals read_coverage_ply(const std::filesystem::path& file,
                                            const Vec3d& offset = Vec3d::Zero());
/// The same for coverage.ply held in memory; `source` names it in messages.
[[nodiscard]] StoredGoals parse_coverage_ply(std::string_view bytes, std::string_view source,
                                             const Vec3d& offset = Vec3d::Zero());

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
