// `surfgrow coverage DIR`: goals, approach poses and a path over the bound planes of a result.
#include <charconv>
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "planes_options.hpp"
#include "result_folder.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"

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

}  // namespace

void add_coverage_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "coverage",
        "Goals, approach poses and a path over a result's bound planes: coverage.json/csv");
    struct Args {
        std::string dir;
        std::string cloud;
        std::string blast = "12mm";
        std::string standoff = "300mm";
        std::string band = "5:40";
        double tilt = 0;
        std::string spacing;
        std::string start;
        int threads = 0;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("dir", args->dir, "Result folder (with planes.json, or give --cloud)")
        ->required();
    cmd->add_option("--cloud", args->cloud,
                    "The cloud the result was grown from: computes planes.json (default "
                    "parameters) when the folder has none");
    cmd->add_option("--blast-radius", args->blast, "A goal covers a disc of this radius")
        ->capture_default_str();
    cmd->add_option("--standoff", args->standoff, "Tool distance from its goal")
        ->capture_default_str();
    cmd->add_option("--angle-band", args->band,
                    "Allowed angle between tool axis and normal, MIN:MAX degrees")
        ->capture_default_str();
    auto* tilt =
        cmd->add_option("--tilt", args->tilt, "Tilt used, degrees within the band (default: MIN)");
    cmd->add_option("--spacing", args->spacing, "Planning grid (default: blast radius / 3)");
    cmd->add_option("--start", args->start, "Tool start position x,y,z with unit");
    cmd->add_option("--threads", args->threads, "Worker threads, 0 = all cores")
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args, tilt] {
        namespace fs = std::filesystem;
        const fs::path dir = args->dir;
        const io::StoredResult result = read_grown_result(dir);
        const double metres = unit_to_metres(result.meta.units, "units in surfaces.json");
        CoverageConfig config;
        config.blast_radius = parse_length_m(args->blast, "--blast-radius") / metres;
        config.standoff = parse_length_m(args->standoff, "--standoff") / metres;
        std::tie(config.min_angle_deg, config.max_angle_deg) = parse_band(args->band);
        if (tilt->count() > 0) config.tilt_deg = args->tilt;
        if (!args->spacing.empty()) {
            config.sample_spacing = parse_length_m(args->spacing, "--spacing") / metres;
            if (!(config.sample_spacing > 0))
                throw Error(ErrorCode::kInvalidParameter, "--spacing must be positive");
        }
        if (!args->start.empty())
            config.start =
                parse_vec3_length_m(args->start, "--start") / metres - result.meta.offset;
        config.threads = args->threads;
        if (!(config.blast_radius > 0))
            throw Error(ErrorCode::kInvalidParameter, "--blast-radius must be positive");
        validate(config);

        io::OutputTransaction tx(dir);
        BoundPlanes planes;
        std::error_code ec;
        if (fs::exists(dir / "planes.json", ec)) {
            planes = io::read_planes_json(dir / "planes.json").planes;
            if (planes.stats.patches != result.surfaces.size())
                throw Error(
                    ErrorCode::kMalformedInput,
                    cat({(dir / "planes.json").string(), " was computed from ",
                         std::to_string(planes.stats.patches), " surfaces but ",
                         (dir / "surfaces.json").string(), " has ",
                         std::to_string(result.surfaces.size()), ": run `surfgrow planes` again"}));
        } else if (!args->cloud.empty()) {
            const GrownFolder f = read_grown_folder(dir, args->cloud);
            planes = compute_bound_planes(
                f.cloud, f.result.surfaces, f.labels,
                PlanesOptions{}.config(metres, f.result.config.mu, args->threads));
            stage_planes(tx, planes, result.meta, false);
        } else {
            throw Error(ErrorCode::kCannotOpen,
                        cat({(dir / "planes.json").string(), " is missing: run `surfgrow planes ",
                             dir.string(), " --cloud CLOUD` first, or give --cloud"}));
        }
        const CoveragePlan plan = plan_coverage(planes, result.surfaces, config);
        tx.add("coverage.json",
               [&](std::ostream& o) { io::write_coverage_json(o, plan, result.meta); });
        tx.add("coverage.csv",
               [&](std::ostream& o) { io::write_coverage_csv(o, plan, result.meta); });
        tx.commit();
        if (!args->quiet) std::cout << coverage_summary(plan, result.meta.units) << std::endl;
    });
}

}  // namespace surfgrow::cli
