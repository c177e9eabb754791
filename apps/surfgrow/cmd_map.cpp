// `surfgrow map SCANS... -o OUT [--watch DIR]`: mapping while scanning. Raw scans are added one
// at a time to one map (pipeline/map.hpp); after each the result folder is refreshed as one
// transaction, so a planner reading OUT always sees the map of a whole number of scans.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "coverage_options.hpp"
#include "grow_options.hpp"
#include "grow_pipeline.hpp"
#include "planes_options.hpp"
#include "scan_job.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/calibration_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"
#include "surfgrow/pipeline/map.hpp"
#include "surfgrow/scanner/calibration.hpp"
#include "surfgrow/scanner/fuse.hpp"

namespace surfgrow::cli {

namespace {

namespace fs = std::filesystem;

// The scan-*.sgraw files in `dir` not yet in `seen`, in name order (scan order).
std::vector<std::string> new_scans(const std::string& dir, const std::set<std::string>& seen) {
    std::vector<std::string> found;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        // Whole files only: acquire and scan write under a hidden name and rename.
        if (name.starts_with(".") || e.path().extension() != ".sgraw") continue;
        if (!seen.count(e.path().string())) found.push_back(e.path().string());
    }
    if (ec) throw Error(ErrorCode::kCannotOpen, cat({"cannot list ", dir, ": ", ec.message()}));
    std::sort(found.begin(), found.end());
    return found;
}

}  // namespace

void add_map_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "map",
        "Map scan by scan: each raw scan's points join the surfaces already mapped or grow new "
        "ones, and the result folder is refreshed after each (--watch: as scans arrive)");
    struct Args {
        std::vector<std::string> raws;
        std::string out = "map";
        std::string watch;
        std::string idle = "60s";
        long long until = 0;
        std::string calibration;
        bool allow_partial = false;
        int trim = 1;
        double join_tolerance = MapConfig{}.join_tolerance;
        GrowOptions grow;
        OutputChoice outputs;
        PlanesOptions planes;
        CoverageOptions coverage;
        bool no_planes = false;
        bool no_coverage = false;
        bool quiet = false;
        double veil_angle = scanner::VeilFilter{}.angle_deg;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("raw", args->raws, "Raw scans (.sgraw) in scan order, or folders of them");
    cmd->add_option("-o,--out", args->out, "Output folder, refreshed after each scan")
        ->capture_default_str();
    cmd->add_option("--watch", args->watch,
                    "Then take each new scan-*.sgraw appearing in this folder (surfgrow acquire "
                    "-o FOLDER), in name order, until none came for --idle");
    cmd->add_option("--idle", args->idle, "With --watch: stop after this long without a scan")
        ->capture_default_str();
    add_count_option(*cmd, "--scans", args->until,
                     "With --watch: stop once this many scans are mapped (0: no limit)");
    cmd->add_option("--calibration", args->calibration,
                    "Mounting to convert with (surfgrow calibrate's file)");
    cmd->add_flag("--allow-partial", args->allow_partial,
                  "Map scans an acquisition left partial (a device failed mid-scan)");
    cmd->add_option("--trim", args->trim, "Readings trimmed from each end, q of eq. (1)")
        ->capture_default_str();
    cmd->add_option("--join-tolerance", args->join_tolerance,
                    "A new point joins a mapped surface within this many times its tolerance")
        ->capture_default_str();
    args->grow.add_to(*cmd);
    cmd->add_flag("!--no-picture", args->outputs.picture, "Do not render surfaces.png");
    cmd->add_flag("--labels-txt", args->outputs.files.labels_txt,
                  "Also write labels.txt (the labels as text, one per line)");
    add_veil_option(*cmd, args->veil_angle);
    cmd->add_flag("-q,--quiet", args->quiet, "No line per scan on stdout");
    auto* robot = cmd->add_option_group("Robot outputs", "Refreshed after each scan");
    robot->add_flag("--no-planes", args->no_planes, "No planes (nor coverage)");
    robot->add_flag("--no-coverage", args->no_coverage, "No coverage");
    robot->add_flag("!--no-occupancy", args->outputs.files.occupancy, "No occupancy");
    robot->add_flag("!--no-octomap", args->outputs.files.octomap, "No environment.bt");
    args->planes.add_to(*cmd->add_option_group("Bound planes (planes.json, planes.ply)"));
    args->coverage.add_to(*cmd->add_option_group("Coverage (coverage.json, coverage.ply)"));
    cmd->callback([args] {
        if (args->raws.empty() && args->watch.empty())
            throw Error(ErrorCode::kUsage, "map: give raw scans, --watch FOLDER, or both");
        const CloudUnits units = args->grow.units();
        if (units.metres != 1.0)
            throw Error(ErrorCode::kUsage, "map: raw scans are in metres; leave out --units");
        const std::chrono::milliseconds idle = parse_duration(args->idle, "--idle", 0, 86400000);
        MapConfig config;
        config.join_tolerance = args->join_tolerance;
        PipelineConfig& pc = config.pipeline;
        pc.grow = args->grow.config(units);
        pc.planes.reset();
        pc.coverage.reset();
        if (!args->no_planes) {
            pc.planes = args->planes.config(units.metres, pc.grow.mu, pc.grow.threads);
            if (!args->no_coverage)
                pc.coverage = args->coverage.config(units.metres, Vec3d::Zero(), pc.grow.threads);
            args->outputs.files.coverage_csv = args->coverage.csv;
        }
        pc.occupancy = args->outputs.files.occupancy || args->outputs.files.octomap;
        scanner::FuseOptions fuse;
        fuse.trim_q = args->trim;
        fuse.allow_partial = args->allow_partial;
        fuse.veil.angle_deg = args->veil_angle;
        std::optional<scanner::Calibration> calibration;
        if (!args->calibration.empty() && args->calibration != "none")
            calibration = io::read_calibration_file(args->calibration);
        Map map(config);
        // environment.bt after each scan: only the new scan's rays are cast.
        io::OctomapCarver carver;

        std::set<std::string> seen;
        const auto add = [&](const std::string& file) {
            seen.insert(file);
            scanner::RawScan raw = io::read_raw_scan(file);
            if (calibration) scanner::apply_calibration(raw, *calibration);
            refuse_partial(file, raw, fuse.allow_partial, "maps");
            PointCloud points;
            scanner::FuseReport fused;
            try {
                points = scanner::fuse_scans(std::span(&raw, 1), fuse, &fused);
            } catch (const Error& e) {
                throw Error(e.code(), cat({file, ": ", e.what()}));
            }
            const Stopwatch watch;
            (void)map.add_scan(points, raw.pose.translation());
            GrowRun run;
            write_outputs(map.cloud(), map.pipeline_config(), map.result(), run, args->out,
                          args->outputs, units, fs::path(file).filename().string(), &carver);
            if (args->quiet) return;
            const MapUpdate& u = map.last_update();
            char buf[400];
            std::snprintf(
                buf, sizeof buf,
                "scan %zu (%s): %llu points%s, %llu joined the map, %llu grew %llu surfaces; "
                "map: %s; %.2f s (join %.3f, grow %.3f, outputs %.3f, write %.3f)",
                u.scan, fs::path(file).filename().string().c_str(),
                static_cast<unsigned long long>(u.points),
                fused.veil_points.empty() || fused.veil_points[0] == 0
                    ? ""
                    : cat({" (", std::to_string(fused.veil_points[0]), " mixed pixels dropped)"})
                          .c_str(),
                static_cast<unsigned long long>(u.joined), static_cast<unsigned long long>(u.grown),
                static_cast<unsigned long long>(u.new_surfaces),
                summary_line(map.result().grow.stats).c_str(), watch.seconds(), u.join_seconds,
                u.grow_seconds, u.outputs_seconds, run.write_seconds);
            std::cout << buf << std::endl;
        };
        if (!args->raws.empty())
            for (const std::string& file : raw_scan_files(args->raws)) add(file);
        if (args->watch.empty()) return;
        std::error_code ec;
        if (!fs::is_directory(args->watch, ec))
            throw Error(ErrorCode::kCannotOpen, cat({"--watch ", args->watch, ": not a folder"}));
        if (args->until < 0)
            throw Error(ErrorCode::kInvalidParameter, "--scans: 0 (no limit) or more");
        const auto limit = static_cast<std::size_t>(args->until);
        auto last = std::chrono::steady_clock::now();
        for (;;) {
            const std::vector<std::string> found = new_scans(args->watch, seen);
            for (const std::string& file : found) {
                if (limit > 0 && map.scans() >= limit) return;
                add(file);
            }
            if (limit > 0 && map.scans() >= limit) return;
            if (!found.empty()) last = std::chrono::steady_clock::now();
            if (std::chrono::steady_clock::now() - last >= idle) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
    });
}

}  // namespace surfgrow::cli
