#include "coverage_options.hpp"

#include <charconv>
#include <cstdio>

#include "cli_common.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/coverage_io.hpp"

namespace surfgrow::cli {

namespace {

// "5:40" -> {5, 40}.
std::pair<double, double> parse_band(const std::string& text) {
    const auto colon = text.find(':');
    double lo = 0, hi = 0;
    auto number = [](std::string_view s, double& v) {
        const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
        return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty();
    };
    if (colon == std::string::npos || !number(std::string_view(text).substr(0, colon), lo) ||
        !number(std::string_view(text).substr(colon + 1), hi))
        throw Error(ErrorCode::kUsage,
                    cat({"--angle-band: '", text, "' is not MIN:MAX in degrees (e.g. 5:40)"}));
    return {lo, hi};
}

}  // namespace

void CoverageOptions::add_to(CLI::App& cmd) {
    cmd.add_option("--blast-radius", blast,
                   "A goal covers a disc of this radius, with unit (default: the result's mu)");
    cmd.add_option("--standoff", standoff, "Tool distance from its goal")->capture_default_str();
    cmd.add_option("--angle-band", band,
                   "Allowed angle between tool axis and normal, MIN:MAX degrees")
        ->capture_default_str();
    tilt_option =
        cmd.add_option("--tilt", tilt, "Tilt used, degrees within the band (default: MIN)");
    cmd.add_option("--spacing", spacing, "Planning grid (default: blast radius / 3)");
    cmd.add_option("--start", start, "Tool start position x,y,z with unit");
    cmd.add_flag("--coverage-csv", csv,
                 "Also write coverage.csv (the goals as text; coverage.ply holds them in binary)");
}

CoverageConfig CoverageOptions::config(double metres, const Vec3d& offset, int threads) const {
    CoverageConfig c;
    if (!blast.empty()) {
        c.blast_radius = parse_length_m(blast, "--blast-radius") / metres;
        if (!(c.blast_radius > 0))
            throw Error(ErrorCode::kInvalidParameter, "--blast-radius must be positive");
    }
    c.standoff = parse_length_m(standoff, "--standoff") / metres;
    std::tie(c.min_angle_deg, c.max_angle_deg) = parse_band(band);
    if (tilt_option && tilt_option->count() > 0) c.tilt_deg = tilt;
    if (!spacing.empty()) {
        c.sample_spacing = parse_length_m(spacing, "--spacing") / metres;
        if (!(c.sample_spacing > 0))
            throw Error(ErrorCode::kInvalidParameter, "--spacing must be positive");
    }
    if (!start.empty()) c.start = parse_vec3_length_m(start, "--start") / metres - offset;
    c.threads = threads;
    validate(c);
    return c;
}

std::string coverage_summary(const CoveragePlan& plan, const std::string& units) {
    const CoverageStats& s = plan.stats;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%llu goals on %llu planes, %.1f%% covered, tool path %.4g %s, %llu transitions",
                  static_cast<unsigned long long>(s.goals),
                  static_cast<unsigned long long>(s.planes), 100.0 * s.coverage, s.tool_path_length,
                  units.c_str(), static_cast<unsigned long long>(s.transitions));
    return buf;
}

}  // namespace surfgrow::cli
