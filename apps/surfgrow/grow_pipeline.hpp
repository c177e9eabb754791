// Grow a cloud and publish every output of `surfgrow grow`: shared by `grow` and `demo`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "surfgrow/core/bound_planes.hpp"
#include "surfgrow/core/coverage.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/render/image.hpp"

namespace surfgrow::cli {

/// Which files to write besides surfaces.ply / surfaces.json / run.json. The robot outputs are on
/// by default: `surfgrow grow` leaves everything a planner needs next to the surfaces.
struct OutputChoice {
    bool labels = true;   ///< labels.txt
    bool csv = false;     ///< surfaces.csv
    bool picture = true;  ///< surfaces.png (iso view)
    /// planes.json and planes.ply (bound planes); mu and threads are taken from the grow config.
    std::optional<BoundPlaneConfig> planes = BoundPlaneConfig{};
    bool planes_obj = false;  ///< also planes.obj
    /// coverage.json and coverage.csv over the bound planes (only when planes are computed).
    std::optional<CoverageConfig> coverage = CoverageConfig{};
    bool occupancy = true;  ///< occupancy.ply and occupancy.json
    bool octomap = true;    ///< environment.bt (OctoMap, free space carved from the scan origins)
    bool collision = true;  ///< collision_spheres.json
};

/// One line per robot output that was written, for --stats: planes, coverage, occupancy.
struct RobotSummary {
    std::string planes;
    std::string coverage;
    std::string occupancy;
};

/// The cloud's length unit and how it maps to metres (for messages and the files' "units").
struct CloudUnits {
    std::string name = "m";
    double metres = 1.0;  ///< metres per cloud unit
};

struct GrowRun {
    GrowResult result;
    std::optional<BoundPlanes> planes;  ///< when computed (OutputChoice::planes)
    RobotSummary robot;
    double read_seconds = 0.0;
    double write_seconds = 0.0;
};

/// Grows `cloud` with `config` and writes the outputs into `out_dir` as one transaction: either
/// every file appears (replacing older ones) or none does.
GrowRun grow_and_write(const PointCloud& cloud, const GrowerConfig& config,
                       const std::filesystem::path& out_dir, const OutputChoice& outputs,
                       const CloudUnits& units, const std::string& input_name, double read_seconds);

/// The default picture of a result: every surface as a disk, iso view, legend line.
render::Image render_surfaces(const GrowResult& result, const std::string& units, int threads);

/// The one-line summary: "276480 points -> 5231 surfaces, 99.4% registered, 52.9x reduction, 0.041
/// s".
std::string summary_line(const GrowStats& stats);

/// Detail lines for --stats: rejections, both registration figures, registered % by range band.
std::string stats_table(const GrowStats& stats, const CloudUnits& units);

/// Advice for a result that registers little because the cloud is too sparse for mu, or "" if
/// none applies. Printed on stderr: the parameters are the user's to change, not ours.
std::string sparsity_hint(const GrowStats& stats, const GrowerConfig& config,
                          const CloudUnits& units);

/// A progress callback for GrowerConfig::progress that draws on stderr when it is a terminal,
/// or nothing otherwise.
std::function<void(std::string_view, double)> terminal_progress();

}  // namespace surfgrow::cli
