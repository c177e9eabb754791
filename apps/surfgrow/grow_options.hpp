// The growing options shared by `grow`, `demo` and `sweep`: parsed with units, checked, mapped
// to a GrowerConfig in the cloud's own units.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "grow_pipeline.hpp"
#include "surfgrow/core/grower_config.hpp"

namespace surfgrow::cli {

struct GrowOptions {
    std::string mu = "12mm";
    int min_pts = 10;
    double alpha = GrowerConfig{}.alpha;
    std::string plane_test = "disk";
    double min_spread = GrowerConfig{}.min_spread;
    double max_incidence = GrowerConfig{}.max_incidence_deg;
    double noise_sigmas = GrowerConfig{}.noise_sigmas;
    std::string plane_tol;  // empty: mu
    std::string mu_max;     // empty: the library's default (8 mu); "off": mu
    int min_new = 1;
    double pool_angle = GrowerConfig{}.pool_angle_deg;
    bool no_attach = false;
    std::uint64_t seed = 1;
    int threads = 0;
    std::string cloud_units = "m";
    std::string viewpoint;
    std::string crop_box;
    std::string crop_radius;
    std::string crop_center;
    std::string range_band = "1m";

    /// Registers the options on a subcommand.
    void add_to(CLI::App& cmd);
    /// The cloud's units from --units. Throws Error(kUsage).
    [[nodiscard]] CloudUnits units() const;
    /// The configuration in the cloud's units. Throws Error(kUsage) for bad syntax and
    /// Error(kInvalidParameter) for values out of range.
    [[nodiscard]] GrowerConfig config(const CloudUnits& units) const;
};

}  // namespace surfgrow::cli
