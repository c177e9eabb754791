// `surfgrow scan2cloud RAW... [--poses FILE] -o cloud.ply`: filter (eq. 1), convert and fuse
// raw scans into one cloud that keeps each point's scan.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "scan_job.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/calibration_file.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"

namespace surfgrow::cli {

void add_scan2cloud_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "scan2cloud", "Filter (eq. 1), convert and fuse raw scans (.sgraw) into one point cloud");
    struct Args {
        std::vector<std::string> raws;
        std::string poses;
        std::string out;
        int trim = 1;
        std::string min_range;
        std::string max_range;
        bool allow_partial = false;
        std::string calibration;
        bool quiet = false;
        double veil_angle = scanner::VeilFilter{}.angle_deg;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("raw", args->raws,
                    "Raw scan files (.sgraw) in scan order, or a folder of them (surfgrow scan -o)")
        ->required();
    cmd->add_option("--poses", args->poses,
                    "Poses file (one per raw scan, in order; default: each scan's own pose)");
    cmd->add_option("-o,--out", args->out,
                    "Output cloud (.ply keeps the scan per point and the scan origins)")
        ->required();
    cmd->add_option("--trim", args->trim, "Readings trimmed from each end, q of eq. (1); n > 2q")
        ->capture_default_str();
    cmd->add_option("--min-range", args->min_range,
                    "Drop readings nearer than this (default: the scan's laser limit)");
    cmd->add_option("--max-range", args->max_range,
                    "Drop readings farther than this (default: the scan's laser limit)");
    cmd->add_option("--calibration", args->calibration,
                    "Mounting to convert with (surfgrow calibrate's file); default: "
                    "calibration.json in a folder of scans given, if there is one; none: the "
                    "scans' own");
    cmd->add_flag("--allow-partial", args->allow_partial,
                  "Fuse scans an acquisition left partial (a device failed mid-scan)");
    add_veil_option(*cmd, args->veil_angle);
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args] {
        namespace fs = std::filesystem;
        std::string calibration = args->calibration;
        if (calibration.empty())
            for (const std::string& arg : args->raws) {
                std::error_code ec;
                if (fs::is_regular_file(fs::path(arg) / "calibration.json", ec))
                    calibration = (fs::path(arg) / "calibration.json").string();
            }
        if (calibration == "none") calibration.clear();
        args->raws = raw_scan_files(args->raws);
        std::vector<scanner::RawScan> raws;
        for (const std::string& file : args->raws) raws.push_back(io::read_raw_scan(file));
        if (!args->poses.empty()) {
            const std::vector<scanner::Pose> poses = io::read_poses_file(args->poses);
            if (poses.size() != raws.size())
                throw Error(ErrorCode::kInvalidParameter,
                            cat({args->poses, ": ", std::to_string(poses.size()), " poses for ",
                                 std::to_string(raws.size()), " raw scans"}));
            for (std::size_t k = 0; k < raws.size(); ++k) raws[k].pose = poses[k];
        }
        if (!calibration.empty()) {
            const scanner::Calibration c = io::read_calibration_file(calibration);
            for (scanner::RawScan& raw : raws) scanner::apply_calibration(raw, c);
        }
        // Each scan against its own laser's limits, with the file named in the message.
        scanner::FuseOptions fuse;
        for (std::size_t k = 0; k < raws.size(); ++k) {
            try {
                fuse = fuse_options(raws[k].spec.readings_per_ray, args->trim, args->min_range,
                                    args->max_range, raws[k].spec.laser);
            } catch (const Error& e) {
                if (e.code() == ErrorCode::kUsage) throw;
                throw Error(e.code(), cat({args->raws[k], ": ", e.what()}));
            }
        }
        fuse.allow_partial = args->allow_partial;
        fuse.veil.angle_deg = args->veil_angle;
        for (std::size_t k = 0; k < raws.size(); ++k)
            refuse_partial(args->raws[k], raws[k], fuse.allow_partial, "fuses");
        scanner::FuseReport fused;
        const PointCloud cloud = scanner::fuse_scans(raws, fuse, &fused);
        io::WriteOptions options;
        options.write_scans = true;
        io::write_cloud(args->out, cloud, options);
        if (!args->quiet)
            std::cout << raws.size() << " scans -> " << cloud.size() << " points"
                      << (calibration.empty() ? "" : " (calibrated by " + calibration + ")")
                      << veil_summary(fused) << std::endl;
    });
}

}  // namespace surfgrow::cli
