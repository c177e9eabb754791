// `surfgrow study -o study/`: the paper's results over many scans (section 5.4, Figs. 7 and 8).
// Simulates a scene from several poses, then grows clouds of increasing size cut from the fused
// scans and writes points, time per stage, surfaces, registered % and data reduction per test as
// CSV and plots.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <span>

#include "cli_common.hpp"
#include "commands.hpp"
#include "grow_options.hpp"
#include "scan_job.hpp"
#include "study_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/version.hpp"

namespace surfgrow::cli {

namespace {

namespace fs = std::filesystem;

constexpr int kMaxPoses = 64;
constexpr std::uint64_t kMinSize = 1000;
constexpr std::uint64_t kMaxSize = 100'000'000;

struct StudyArgs {
    std::string out = "study";
    std::string scene = "ibeam-channel";
    int poses = 5;
    std::string sizes = "10k:1M";
    int steps = 12;
    int repeat = 1;
    GrowOptions grow;
    bool require_plots = false;
    bool quiet = false;
};

// The `count` points of `cloud` nearest to `center` (ties by index), in their original order,
// with everything else a point carries; `radius` is the farthest one's distance.
PointCloud nearest_points(const PointCloud& cloud, const Vec3d& center, std::size_t count,
                          double& radius) {
    std::vector<std::pair<double, std::uint32_t>> by_distance(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
        by_distance[i] = {(cloud.points[i].cast<double>() - center).squaredNorm(),
                          static_cast<std::uint32_t>(i)};
    count = std::min(count, by_distance.size());
    std::nth_element(by_distance.begin(), by_distance.begin() + std::ptrdiff_t(count) - 1,
                     by_distance.end());
    radius = std::sqrt(by_distance[count - 1].first);
    std::vector<std::uint32_t> keep(count);
    for (std::size_t i = 0; i < count; ++i) keep[i] = by_distance[i].second;
    std::sort(keep.begin(), keep.end());

    PointCloud out;
    out.offset = cloud.offset;
    out.viewpoint = cloud.viewpoint;
    out.scan_origins = cloud.scan_origins;
    out.points.reserve(count);
    for (const std::uint32_t i : keep) out.points.push_back(cloud.points[i]);
    if (cloud.has_scan_index())
        for (const std::uint32_t i : keep) out.scan_index.push_back(cloud.scan_index[i]);
    if (cloud.has_labels())
        for (const std::uint32_t i : keep) out.labels.push_back(cloud.labels[i]);
    return out;
}

void run(const StudyArgs& a) {
    // Every option is checked before the simulation.
    const CloudUnits units = a.grow.units();
    if (units.name != "m")
        throw Error(ErrorCode::kUsage, "study: the simulated clouds are in metres (no --units)");
    const GrowerConfig config = a.grow.config(units);
    check_count(a.poses, "--poses", kMaxPoses);
    if (a.repeat < 1 || a.repeat > kMaxRepeat)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--repeat must be between 1 and ", std::to_string(kMaxRepeat), ", got ",
                         std::to_string(a.repeat)}));
    const std::vector<std::uint64_t> sizes =
        parse_size_sweep(a.sizes, "--sizes", a.steps, kMinSize, kMaxSize);
    const fs::path out(a.out);
    std::error_code ec;
    if (fs::exists(out, ec) && !fs::is_directory(out, ec))
        throw Error(ErrorCode::kCannotWrite,
                    cat({"cannot write ", a.out, ": it exists and is not a folder"}));

    ScanSettings scan;
    scan.scene = a.scene;
    scan.poses = std::to_string(a.poses);
    scan.seed = a.grow.seed;
    const ScanData data = run_scan(scan);
    const std::span<const scanner::RawScan> raws(data.raws);
    if (sizes.back() > data.cloud.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--sizes: ", std::to_string(sizes.back()), " points, but ",
                         std::to_string(a.poses), " poses of ", a.scene, " give ",
                         std::to_string(data.cloud.size()), ": raise --poses or lower --sizes"}));

    // Each test: the fewest poses whose fused cloud holds enough points, cut down to the points
    // nearest the middle of their scan origins (a spherical workspace: the density is the scan's).
    CsvTable table;
    table.header = {"test", "poses", "radius_m"};
    for (std::string& c : result_columns(false)) table.header.push_back(std::move(c));
    for (std::string& c : timing_columns()) table.header.push_back(std::move(c));
    const bool progress = stderr_is_terminal();
    const Stopwatch watch;
    std::size_t k = 0;
    PointCloud fused;
    for (std::size_t test = 0; test < sizes.size(); ++test) {
        const std::uint64_t size = sizes[test];
        while (fused.size() < size) {
            ++k;
            fused = k == raws.size() ? data.cloud : scanner::fuse_scans(raws.first(k), data.fuse);
        }
        Vec3d center = Vec3d::Zero();
        for (std::size_t s = 0; s < k; ++s) center += fused.scan_origins[s];
        center /= double(k);
        double radius = 0.0;
        const PointCloud cloud = nearest_points(fused, center, size, radius);
        std::vector<StageTimes> times;
        GrowResult result;
        for (int r = 0; r < a.repeat; ++r) {
            if (progress) {
                std::fprintf(stderr, "\rstudy %3zu/%zu  %9llu points", test + 1, sizes.size(),
                             static_cast<unsigned long long>(size));
                std::fflush(stderr);
            }
            result = grow_surfaces(cloud, config);
            times.push_back(result.stats.seconds);
        }

        std::vector<std::string> row = {std::to_string(test + 1), std::to_string(k),
                                        fixed(radius, 4)};
        for (std::string& f : result_fields(result.stats, nullptr)) row.push_back(std::move(f));
        for (std::string& f : timing_fields(median_run(times))) row.push_back(std::move(f));
        table.rows.push_back(std::move(row));
    }
    if (progress) std::fprintf(stderr, "\r%60s\r", "");
    const double seconds = watch.seconds();

    const std::vector<std::pair<std::string, std::string>> csv_files = {
        {"study.csv", table.text()}};
    const std::string title = cat({"surfgrow study: ", data.scene->description().name, ", ",
                                   std::to_string(a.poses), " poses, mu ", format_length(config.mu),
                                   ", min_pts ", std::to_string(config.min_pts)});
    const Plots plots = draw_plots("study", csv_files, {"scaling.png", "stages.png"}, title);
    if (!plots.drawn && a.require_plots)
        throw Error(ErrorCode::kCannotWrite,
                    cat({"cannot draw the plots (--require-plots): ", plots.why_not}));

    nlohmann::json files = nlohmann::json::array({"study.csv"});
    for (const auto& [name, bytes] : plots.files) files.push_back(name);
    const nlohmann::json record = {
        {"format", "surfgrow-study"},
        {"version", 1},
        {"surfgrow_version", SURFGROW_VERSION},
        {"scene", data.scene->description().name},
        {"scene_source", a.scene},
        {"poses", a.poses},
        {"points_simulated", data.cloud.size()},
        {"seed", config.seed},
        {"repeat", a.repeat},
        {"mu_m", config.mu},
        {"min_pts", config.min_pts},
        {"tests", sizes.size()},
        {"files", files},
    };
    publish_study(out, csv_files, plots, "study.json", record, "study.csv is");
    if (!a.quiet) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.1f s", seconds);
        std::cout << cat({"study: ", std::to_string(sizes.size()), " tests of ",
                          std::to_string(sizes.front()), "..", std::to_string(sizes.back()),
                          " points from ", std::to_string(a.poses), " poses of ",
                          data.scene->description().name, ", grown in ", buf, " -> ", a.out,
                          plots.drawn ? " (CSV and plots)" : " (CSV only)"})
                  << std::endl;
    }
}

}  // namespace

void add_study_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "study",
        "Grow simulated scans of increasing size: time per stage, surfaces, registered %, data "
        "reduction against points, as CSV and plots (paper Figs. 7 and 8)");
    auto a = std::make_shared<StudyArgs>();
    cmd->add_option("-o,--out", a->out,
                    "Output folder: study.csv, scaling.png, stages.png, study.json (written as a "
                    "whole)")
        ->capture_default_str();
    cmd->add_option("--scene", a->scene,
                    "Built-in scene (ibeam-channel, room-corner, pipes, corridor, stairs) or a "
                    "scene file (.json)")
        ->capture_default_str();
    cmd->add_option("--poses", a->poses,
                    "Scans simulated along the scene's path; a test uses the fewest that hold its "
                    "points")
        ->capture_default_str();
    cmd->add_option("--sizes", a->sizes,
                    "Points per test: FROM:TO (log-spaced, see --steps) or a list 20k,50k,100k")
        ->capture_default_str();
    cmd->add_option("--steps", a->steps, "Number of tests in a FROM:TO range")
        ->capture_default_str();
    cmd->add_option("--repeat", a->repeat,
                    "Runs per test; the CSV's times are those of the run with the median total")
        ->capture_default_str();
    a->grow.add_to(*cmd);
    cmd->get_option("--seed")->description("Seed of the simulated noise and of the home points");
    cmd->add_flag("--require-plots", a->require_plots,
                  "Fail (exit 7, nothing written) when the plots cannot be drawn, instead of a "
                  "warning");
    cmd->add_flag("-q,--quiet", a->quiet, "No summary line on stdout");
    cmd->callback([a] { run(*a); });
}

}  // namespace surfgrow::cli
