#include "grow_pipeline.hpp"

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene_builder.hpp"

namespace surfgrow::cli {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

render::Image render_surfaces(const GrowResult& result, const std::string& units, int threads) {
    render::Scene scene = render::scene_from_surfaces(result.surfaces);
    scene.legend = render::legend_line(result.stats.points_in, result.stats.surfaces,
                                       result.stats.registered_fraction());
    render::RenderOptions options;
    options.units = units;
    options.threads = threads;
    // Normals face the sensor unless no viewpoint was known; then show both sides of every disk.
    if (result.stats.orientation == OrientationSource::kUp)
        options.back_faces = render::BackFaces::kShow;
    return render::render_scene(scene, options);
}

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

std::function<void(std::string_view, double)> terminal_progress() {
    if (!stderr_is_terminal()) return {};
    return [](std::string_view stage, double fraction) {
        std::fprintf(stderr, "\r%-8.*s %5.1f%%", static_cast<int>(stage.size()), stage.data(),
                     100.0 * fraction);
        if (stage == "finish") std::fprintf(stderr, "\r%20s\r", "");
        std::fflush(stderr);
    };
}

GrowRun grow_and_write(const PointCloud& cloud, const GrowerConfig& config,
                       const std::filesystem::path& out_dir, const OutputChoice& outputs,
                       const CloudUnits& units, const std::string& input_name,
                       double read_seconds) {
    GrowRun run;
    run.read_seconds = read_seconds;
    run.result = grow_surfaces(cloud, config);
    const GrowResult& r = run.result;

    const auto t0 = Clock::now();
    io::ResultMeta meta;
    meta.units = units.name;
    meta.offset = cloud.offset;
    meta.input = input_name;
    io::OutputTransaction tx(out_dir);
    tx.add("surfaces.ply", [&](std::ostream& o) { io::write_surfaces_ply(o, r.surfaces, meta); });
    tx.add("surfaces.json", [&](std::ostream& o) { io::write_result_json(o, r, config, meta); });
    if (outputs.labels)
        tx.add("labels.txt", [&](std::ostream& o) { io::write_labels_txt(o, r.labels); });
    if (outputs.csv)
        tx.add("surfaces.csv",
               [&](std::ostream& o) { io::write_surfaces_csv(o, r.surfaces, meta); });
    if (outputs.picture) {
        const render::Image image = render_surfaces(r, units.name, config.threads);
        tx.add("surfaces.png", [&](std::ostream& o) { render::write_png(image, o); });
    }
    run.write_seconds = since(t0);
    // run.json: what varies between identical runs (timings, threads), kept out of the results.
    const StageTimes& t = r.stats.seconds;
    const nlohmann::json record = {
        {"surfgrow_version", SURFGROW_VERSION},
        {"input", input_name},
        {"threads", config.threads},
        {"seconds",
         {{"read", read_seconds},
          {"index", t.index},
          {"grow", t.grow},
          {"attach", t.attach},
          {"finish", t.finish},
          {"algorithm", t.total()},
          {"write", run.write_seconds}}},
        {"summary", summary_line(r.stats)},
    };
    tx.add("run.json", [&](std::ostream& o) { o << record.dump(2) << "\n"; });
    tx.commit();
    return run;
}

}  // namespace surfgrow::cli
