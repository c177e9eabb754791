#include "grow_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "coverage_options.hpp"
#include "planes_options.hpp"
#include "surfaces_picture.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/result_outputs.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene_builder.hpp"
#include "surfgrow/version.hpp"

namespace surfgrow::cli {

std::string summary_line(const GrowStats& s) {
    char buf[256];
    std::snprintf(
        buf, sizeof buf, "%llu points -> %llu surfaces, %.1f%% registered, %.1fx reduction, %.3f s",
        static_cast<unsigned long long>(s.points_in), static_cast<unsigned long long>(s.surfaces),
        100.0 * s.registered_fraction(), s.data_reduction(), s.seconds.total());
    std::string line = buf;
    if (s.invalid_points || s.cropped_points) {
        std::snprintf(buf, sizeof buf, " (%llu invalid, %llu outside the workspace)",
                      static_cast<unsigned long long>(s.invalid_points),
                      static_cast<unsigned long long>(s.cropped_points));
        line += buf;
    }
    return line;
}

std::string stats_table(const GrowStats& s, const CloudUnits& units) {
    auto pct = [](std::uint64_t a, std::uint64_t b) {
        return b ? 100.0 * double(a) / double(b) : 0.0;
    };
    char buf[256];
    std::string out;
    std::snprintf(
        buf, sizeof buf,
        "points: %llu in, %llu valid, %llu invalid (NaN/Inf), %llu outside the workspace\n",
        static_cast<unsigned long long>(s.points_in),
        static_cast<unsigned long long>(s.valid_points),
        static_cast<unsigned long long>(s.invalid_points),
        static_cast<unsigned long long>(s.cropped_points));
    out += buf;
    std::snprintf(
        buf, sizeof buf,
        "registered: %.2f%% by growing (the paper's loop), %.2f%% after the leftover pass\n",
        pct(s.registered_grown, s.valid_points), pct(s.registered, s.valid_points));
    out += buf;
    std::snprintf(
        buf, sizeof buf,
        "home points: %llu tried, %llu surfaces, %llu too sparse, %llu not planar, %llu covered; "
        "%llu surfaces with an adapted radius, %llu strips\n",
        static_cast<unsigned long long>(s.homes_tried), static_cast<unsigned long long>(s.surfaces),
        static_cast<unsigned long long>(s.rejected_sparse),
        static_cast<unsigned long long>(s.rejected_nonplanar),
        static_cast<unsigned long long>(s.rejected_covered),
        static_cast<unsigned long long>(s.adapted_surfaces),
        static_cast<unsigned long long>(s.strip_surfaces));
    out += buf;
    if (s.range_known) {
        out += "registered by range from the sensor:\n";
        for (const RangeBand& b : s.range_bands) {
            if (b.points == 0) continue;
            std::snprintf(buf, sizeof buf, "  %6s - %-6s %9llu points  %6.2f%%\n",
                          format_length(b.from * units.metres).c_str(),
                          std::isfinite(b.to) ? format_length(b.to * units.metres).c_str() : "",
                          static_cast<unsigned long long>(b.points), pct(b.registered, b.points));
            out += buf;
        }
    }
    return out;
}

std::string sparsity_hint(const GrowStats& s, const GrowerConfig& config, const CloudUnits& units) {
    if (!s.sparse_for_mu()) return "";
    const bool adaptive = config.max_radius() > config.mu;
    const std::string advice =
        adaptive
            ? cat({"Even the adaptive radius (up to ",
                   length_argument(config.max_radius() * units.metres),
                   ") finds too few: try a larger --mu-max or --mu, or --crop-radius to the "
                   "robot's "
                   "workspace"})
            : cat({"Try --mu-max ", length_argument(4 * config.mu * units.metres),
                   " (adaptive radius), a larger --mu, or --crop-radius to the robot's workspace"});
    const std::string hint =
        cat({"note: only ", std::to_string(static_cast<int>(100 * s.registered_fraction())),
             "% registered: ", std::to_string(s.rejected_sparse), " home points had fewer than ",
             std::to_string(config.min_pts), " neighbours within ",
             format_length(config.mu * units.metres),
             " (points too far apart; the paper's mu suits a ~1 m workspace).\n      ", advice,
             "; --stats shows registration by range."});
    return hint;
}

std::string orientation_hint(const GrowStats& s) {
    if (!s.origin_looks_wrong()) return "";
    const auto share = static_cast<int>(std::lround(
        100.0 * double(s.edge_on_points) / double(std::max<std::uint64_t>(s.registered, 1))));
    return cat({"note: the cloud names no sensor position and its frame origin sees ",
                std::to_string(share),
                "% of the registered points edge-on: it is probably not where the sensor "
                "stood (a map-frame cloud).\n      Normals face the origin where it can tell "
                "and +z elsewhere; give --viewpoint X,Y,Z (or scan2cloud's scan origins) for "
                "normals that face the sensor."});
}

std::function<void(std::string_view, double)> terminal_progress() {
    if (!stderr_is_terminal()) return {};
    return [](std::string_view stage, double fraction) {
        std::fprintf(stderr, "\r%-8.*s %5.1f%%", static_cast<int>(stage.size()), stage.data(),
                     100.0 * fraction);
        if (stage == "done") std::fprintf(stderr, "\r%20s\r", "");
        std::fflush(stderr);
    };
}

GrowRun grow_and_write(const PointCloud& cloud, const PipelineConfig& config,
                       const std::filesystem::path& out_dir, const OutputChoice& outputs,
                       const CloudUnits& units, const std::string& input_name,
                       double read_seconds) {
    const Pipeline pipeline(config);
    GrowRun run;
    run.read_seconds = read_seconds;
    run.result = pipeline.run(cloud);
    write_outputs(cloud, pipeline.config(), run.result, run, out_dir, outputs, units, input_name);
    return run;
}

void write_outputs(const PointCloud& cloud, const PipelineConfig& config, const PipelineResult& r,
                   GrowRun& run, const std::filesystem::path& out_dir, const OutputChoice& outputs,
                   const CloudUnits& units, const std::string& input_name,
                   io::OctomapCarver* carver) {
    const GrowerConfig& grow = config.grow;
    const double read_seconds = run.read_seconds;

    Stopwatch watch;
    io::ResultMeta meta;
    meta.units = units.name;
    meta.offset = cloud.offset;
    meta.input = input_name;
    meta.result_id = io::result_id(r.grow, grow, meta);
    io::OutputTransaction tx(out_dir, io::is_result_file);
    std::span<const std::int32_t> planes;
    if (r.planes) planes = r.planes->plane_of_patch;
    // The pictures are drawn while environment.bt's rays are cast.
    const io::OccupancySummary occupancy = io::stage_result(
        tx, cloud, config, r, meta, outputs.files,
        [&] {
            stage_surfaces_pictures(tx, r.grow.surfaces, r.grow.stats, planes, units.name,
                                    grow.threads, outputs.picture, outputs.close_up);
        },
        carver);
    run.write_seconds = watch.seconds();

    if (r.planes) run.robot.planes = planes_summary(*r.planes, units.name);
    if (r.coverage) run.robot.coverage = coverage_summary(*r.coverage, units.name);
    if (r.occupancy) {
        run.robot.occupancy = cat({std::to_string(occupancy.occupied_cubes), " occupied cubes"});
        if (occupancy.octomap_written)
            run.robot.occupancy += cat(
                {", environment.bt with ", std::to_string(occupancy.octomap.free), " free leaves"});
    }
    // run.json: what varies between identical runs (timings, threads), kept out of the results.
    nlohmann::json robot_seconds = nlohmann::json::object();
    if (r.planes) robot_seconds["planes"] = r.seconds.planes;
    if (r.coverage) robot_seconds["coverage"] = r.seconds.coverage;
    if (r.occupancy) robot_seconds["occupancy"] = r.seconds.occupancy;
    if (occupancy.octomap_written) robot_seconds["environment_bt"] = occupancy.octomap_seconds;
    if (r.collision) robot_seconds["collision"] = r.seconds.collision;
    const StageTimes& t = r.grow.stats.seconds;
    const nlohmann::json record = {
        {"surfgrow_version", SURFGROW_VERSION},
        {"input", input_name},
        {"threads", grow.threads},
        {"seconds",
         {{"read", read_seconds},
          {"index", t.index},
          {"grow", t.grow},
          {"attach", t.attach},
          {"finish", t.finish},
          {"algorithm", t.total()},
          {"write", run.write_seconds},
          {"robot_outputs", robot_seconds}}},
        {"summary", summary_line(r.grow.stats)},
    };
    tx.add("run.json", [&](std::ostream& o) { o << record.dump(2) << "\n"; });
    tx.commit();
}

}  // namespace surfgrow::cli
