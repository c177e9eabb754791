// Simulating a scene's scan from several poses and publishing it: shared by `scan` and `demo`.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/noise_model.hpp"
#include "surfgrow/scanner/raw_scan.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::cli {

/// What to scan and how, as given on the command line.
struct ScanSettings {
    std::string scene = "ibeam-channel";  ///< a built-in scene's name, or a scene file (.json)
    std::string poses = "3";              ///< a count along the scene's scan path, or a poses file
    std::uint64_t seed = 1;
    int readings = 5;  ///< n of eq. (1)
    int trim = 1;      ///< q of eq. (1)
    std::string laser = "urg04lx-paper";
    std::string noise = "datasheet";  ///< "datasheet" or "ideal" (no noise, dropouts, mixed pixels)
    std::string min_range;            ///< fusing limits with unit; empty: the laser's own
    std::string max_range;
    std::string optical_offset = "40mm";  ///< laser optical centre above the tilt axis
    std::string pose_error;               ///< sigma of the recorded poses' translation error
    double pose_error_deg = 0.0;          ///< sigma of the recorded poses' rotation error
    double veil_angle_deg = scanner::VeilFilter{}.angle_deg;  ///< mixed pixels dropped; 0: none

    /// Registers the options on a subcommand (everything but the output folder).
    void add_to(CLI::App& cmd);
};

/// A simulated multi-pose scan and its fused cloud.
struct ScanData {
    std::string scene_source;  ///< the built-in name or the file, as given
    std::unique_ptr<scanner::Scene> scene;
    std::vector<scanner::Pose> poses;
    std::vector<scanner::RawScan> raws;
    scanner::FuseOptions fuse;
    scanner::FuseReport fused;  ///< what fusing left out
    PointCloud cloud;           ///< metres, truth face id per point, scan index and origins
    double simulate_seconds = 0.0;
    double fuse_seconds = 0.0;
};

/// A scene file when `name` names one (or looks like one: .json, a path); a built-in scene
/// otherwise. Throws surfgrow::Error.
scanner::SceneDescription load_scene(const std::string& name);

/// The sensor model called `name`: "datasheet" (URG-04LX) or "ideal". Throws Error(kUsage).
scanner::NoiseModel noise_model(const std::string& name);

/// The optical centre's height above the tilt axis in metres: "0" alone needs no unit, anything
/// else does; under 1 m in size. Throws Error(kUsage) or Error(kInvalidParameter).
double optical_offset_m(const std::string& text);

/// Fusing limits and trim from the settings, checked against `laser` before any work is done.
/// Throws Error(kUsage) for a length without unit, Error(kInvalidParameter) for n <= 2q or limits
/// outside the sensor's.
scanner::FuseOptions fuse_options(int readings, int trim, const std::string& min_range,
                                  const std::string& max_range, const scanner::LaserSpec& laser);

/// Registers --veil-angle (FuseOptions::veil) on a subcommand that fuses raw scans.
void add_veil_option(CLI::App& cmd, double& angle_deg);

/// "; N mixed pixels dropped" for a summary line, or nothing when none were.
std::string veil_summary(const scanner::FuseReport& report);

/// Reads the scene and poses, checks every parameter, then simulates and fuses. Nothing is
/// written. Throws surfgrow::Error for any bad input before the (slow) simulation starts.
ScanData run_scan(const ScanSettings& settings);

/// Writes, as one transaction into `dir`: scan-000.sgraw ... (raw scans with ground truth),
/// cloud.ply (the fused cloud: truth label and scan per point, scan origins), truth-faces.json,
/// scene.json, poses.txt and scan.json (what was simulated, with what).
void write_scan_outputs(const std::filesystem::path& dir, const ScanData& data,
                        const ScanSettings& settings);

/// The raw scan files the arguments name: a file as it is, a folder (`scan -o`, `acquire -o`)
/// as its .sgraw files in name order, which is scan order. A folder without any is
/// Error(kCannotOpen).
std::vector<std::string> raw_scan_files(const std::vector<std::string>& args);

/// Throws Error(kInvalidParameter) naming `file` and why it stopped when `raw` is a partial scan
/// and `allowed` is false ("...; --allow-partial <verb> it").
void refuse_partial(const std::string& file, const scanner::RawScan& raw, bool allowed,
                    std::string_view verb);

/// "scan-007.sgraw".
std::string raw_scan_name(std::size_t k);

}  // namespace surfgrow::cli
