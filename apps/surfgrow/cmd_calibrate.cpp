// `surfgrow calibrate SCANS... [-o calibration.json]`: the optical centre's height above the
// tilt axis and the servo's zero, estimated from scans of one large flat surface, written where
// scan2cloud reads them (docs/scanner.md, "Calibration").
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "scan_job.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/calibration_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"
#include "surfgrow/scanner/calibration.hpp"

namespace surfgrow::cli {

void add_calibrate_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "calibrate",
        "Estimate the laser's optical offset above the tilt axis (and, from scans taken from "
        "places across the surface, the servo's zero) from scans of one large flat surface");
    struct Args {
        std::vector<std::string> raws;
        std::string out;
        int trim = 1;
        std::uint64_t seed = 1;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("raw", args->raws,
                    "Raw scans (.sgraw) of the surface, or a folder of them (surfgrow acquire -o)")
        ->required();
    cmd->add_option("-o,--out", args->out,
                    "Calibration file (default: calibration.json in the scans' folder, where "
                    "scan2cloud finds it)");
    cmd->add_option("--trim", args->trim, "Readings trimmed from each end, q of eq. (1)")
        ->capture_default_str();
    add_seed_option(*cmd, args->seed, "Seed of the search for the surface");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary on stdout");
    cmd->callback([args] {
        namespace fs = std::filesystem;
        std::string out = args->out;
        if (out.empty()) {
            std::error_code ec;
            if (args->raws.size() != 1 || !fs::is_directory(args->raws[0], ec))
                throw Error(ErrorCode::kUsage,
                            "-o: name the calibration file (it goes into the scans' folder only "
                            "when a folder is given)");
            out = (fs::path(args->raws[0]) / "calibration.json").string();
        }
        const std::vector<std::string> files = raw_scan_files(args->raws);
        std::vector<scanner::RawScan> raws;
        for (const std::string& f : files) raws.push_back(io::read_raw_scan(f));
        scanner::CalibrationOptions options;
        options.trim_q = args->trim;
        options.seed = args->seed;
        const scanner::CalibrationResult r = [&] {
            try {
                return scanner::calibrate(raws, options);
            } catch (const Error& e) {  // name the scans the estimate failed on
                std::string named;
                for (const std::string& raw : args->raws)
                    named += (named.empty() ? "" : ", ") + raw;
                throw Error(e.code(), cat({named, ": ", e.what()}));
            }
        }();
        io::write_calibration_file(out, r, files);
        if (args->quiet) return;
        char zero[128] = "not estimated (it needs scans from places across the surface)";
        if (r.zero_estimated)
            std::snprintf(zero, sizeof zero, "%.2f deg +- %.2f deg", r.calibration.tilt_zero_deg,
                          r.zero_sigma_deg);
        char buf[512];
        std::snprintf(buf, sizeof buf,
                      "optical offset %.1f mm +- %.1f mm (the scans say %.1f mm); servo zero %s; "
                      "surface: %zu points, rms %.1f mm -> %.1f mm, bow %.1f mm -> %s",
                      1e3 * r.calibration.optical_offset_m, 1e3 * r.offset_sigma_m,
                      1e3 * raws.front().spec.optical_offset_m.z(), zero, r.points,
                      1e3 * r.rms_before_m, 1e3 * r.rms_after_m, 1e3 * r.bow_m, out.c_str());
        std::cout << buf << std::endl;
    });
}

}  // namespace surfgrow::cli
