// The options of `surfgrow coverage` (lengths with units, the angle band in degrees) and its
// summary line.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "surfgrow/robot/coverage.hpp"

namespace surfgrow::cli {

struct CoverageOptions {
    std::string blast;  // empty: the result's mu
    std::string standoff = "300mm";
    std::string band = "5:40";
    double tilt = 0;
    CLI::Option* tilt_option = nullptr;  // set by add_to(); --tilt counts only when given
    std::string spacing;                 // empty: blast radius / 3
    std::string start;                   // empty: none
    bool csv = false;                    // also coverage.csv

    /// Registers the options on a subcommand (keep the object alive while it parses).
    void add_to(CLI::App& cmd);
    /// The configuration in the cloud's units (`metres` per unit); `offset` is the cloud's, which
    /// --start (in file coordinates) is moved by. Throws Error(kUsage) for bad syntax and
    /// Error(kInvalidParameter) for values out of range.
    [[nodiscard]] CoverageConfig config(double metres, const Vec3d& offset, int threads) const;
};

/// "24990 goals on 322 planes, 99.8% covered, tool path 620.4 m, 321 transitions".
std::string coverage_summary(const CoveragePlan& plan, const std::string& units);

}  // namespace surfgrow::cli
