// Taking one scan with the real or emulated devices and writing it: shared by `acquire` and
// `demo --emulate`.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "surfgrow/scanner/raw_scan.hpp"

namespace surfgrow::cli {

/// How to take a scan, as given on the command line.
struct AcquireSettings {
    std::string out;
    std::string port = "/dev/ttyACM0";
    int baud = 115200;
    std::string servo_port = "/dev/ttyUSB0";
    int servo_baud = 57600;
    int servo_id = 1;
    std::string tilt = "-60deg:60deg:1/3deg";
    int readings = 5;
    std::string optical_offset = "40mm";
    std::string pose;
    std::string timeout = "1s";
    int attempts = 3;
    std::string emulate;  ///< a scene: both devices emulated behind pseudo-terminals
    std::vector<std::string> faults;
    std::string noise = "datasheet";
    std::string true_offset;
    std::string true_zero = "0deg";
    std::uint64_t seed = 1;
    bool quiet = false;  ///< no progress on stderr

    /// Registers the options on a subcommand (all but -q).
    void add_to(CLI::App& cmd);
};

struct AcquiredScan {
    std::filesystem::path file;
    scanner::RawScan scan;
    double seconds = 0.0;
    int retries = 0;
};

/// Checks every setting, takes the scan and writes it (a .sgraw file, or the next scan-NNN.sgraw
/// of a folder). A device failing mid-scan writes the partial scan and throws
/// OutcomeError(kDeviceFailed); one failing before a position is complete writes nothing and
/// throws the same.
[[nodiscard]] AcquiredScan take_scan(const AcquireSettings& settings);

}  // namespace surfgrow::cli
