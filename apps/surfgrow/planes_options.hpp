// The options of `surfgrow planes` (angles in degrees, lengths with units) and its summary line.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "surfgrow/planes/bound_planes.hpp"

namespace surfgrow::cli {

struct PlanesOptions {
    double angle = BoundPlaneConfig{}.max_angle_deg;
    std::string offset;      // empty: from the measured noise
    std::string adjacency;   // empty: mu / 2
    std::string max_gap;     // empty: 5 mu
    bool no_bridge = false;  // never merge across gaps
    std::string resolution;  // empty: mu / 2
    std::string closing;     // empty: from the point spacing
    std::string simplify;    // empty: the resolution
    bool obj = false;

    /// Registers the options on a subcommand.
    void add_to(CLI::App& cmd);
    /// The configuration in the cloud's units (`metres` per unit), for surfaces grown with `mu`.
    /// Throws Error(kUsage) for bad syntax, Error(kInvalidParameter) for values out of range.
    [[nodiscard]] BoundPlaneConfig config(double metres, double mu, int threads) const;
};

/// "5231 surfaces -> 14 planes, 8.36 m2 (2 degenerate)".
std::string planes_summary(const BoundPlanes& planes, const std::string& units);

}  // namespace surfgrow::cli
