// Run the pipeline over a cloud and publish every output of `surfgrow grow`: shared by `grow`
// and `demo`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/io/result_outputs.hpp"
#include "surfgrow/pipeline/pipeline.hpp"
#include "surfgrow/render/image.hpp"

namespace surfgrow::cli {

/// What `surfgrow grow` writes besides the pipeline's results: the files it chooses and the
/// picture.
struct OutputChoice {
    io::ResultFiles files;
    bool picture = true;    ///< surfaces.png: the overview (iso view, coloured by bound plane)
    bool close_up = false;  ///< corner.png: a corner close-up with normals (the demo's)
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
    PipelineResult result;
    RobotSummary robot;
    double read_seconds = 0.0;
    double write_seconds = 0.0;
};

/// Runs the pipeline over `cloud` with `config` and writes the outputs into `out_dir` as one
/// transaction: either every file appears (replacing older ones) or none does.
GrowRun grow_and_write(const PointCloud& cloud, const PipelineConfig& config,
                       const std::filesystem::path& out_dir, const OutputChoice& outputs,
                       const CloudUnits& units, const std::string& input_name, double read_seconds);

/// Writes the outputs of `result` (computed over `cloud` with `config`, as Pipeline::config()
/// gives it) into `out_dir` as one transaction; sets run.write_seconds and run.robot (its own
/// result is not read: a map's is its own, not copied).
/// With a `carver` (map: the same one after every scan), environment.bt casts only the rays of
/// the points added since.
void write_outputs(const PointCloud& cloud, const PipelineConfig& config,
                   const PipelineResult& result, GrowRun& run, const std::filesystem::path& out_dir,
                   const OutputChoice& outputs, const CloudUnits& units,
                   const std::string& input_name, io::OctomapCarver* carver = nullptr);

/// The one-line summary: "276480 points -> 5231 surfaces, 99.4% registered, 52.9x reduction, 0.041
/// s".
std::string summary_line(const GrowStats& stats);

/// Detail lines for --stats: rejections, both registration figures, registered % by range band.
std::string stats_table(const GrowStats& stats, const CloudUnits& units);

/// Advice for a result that registers little because the cloud is too sparse for mu, or "" if
/// none applies. Printed on stderr: the parameters are the user's to change, not ours.
std::string sparsity_hint(const GrowStats& stats, const GrowerConfig& config,
                          const CloudUnits& units);

/// Advice for normals that faced a guessed frame origin which sees much of the cloud edge-on
/// (GrowStats::origin_looks_wrong: a map-frame cloud), or "". Printed on stderr.
std::string orientation_hint(const GrowStats& stats);

/// A progress callback for GrowerConfig::progress that draws on stderr when it is a terminal,
/// or nothing otherwise; it clears its line at the pipeline's "done".
std::function<void(std::string_view, double)> terminal_progress();

}  // namespace surfgrow::cli
