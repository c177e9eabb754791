// `surfgrow demo [-o demo]`: the README's main job. Simulates the paper's I-beam channel from a
// few poses, grows surfaces, evaluates them against the ground truth, writes everything.
#include <charconv>
#include <iostream>

#include "acquire_job.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "eval_job.hpp"
#include "grow_options.hpp"
#include "grow_pipeline.hpp"
#include "scan_job.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/eval/report_text.hpp"
#include "surfgrow/pipeline/map.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"

namespace surfgrow::cli {

namespace {

struct EmulatedDemo {
    scanner::Scene scene;
    PointCloud cloud;
    GrowRun run;
};

// The scans taken through the emulated devices into out/scan/, mapped one by one into out/.
EmulatedDemo emulated_demo(const std::filesystem::path& out, const ScanSettings& scan,
                           const PipelineConfig& config, const OutputChoice& outputs,
                           const CloudUnits& units) {
    namespace fs = std::filesystem;
    const std::vector<scanner::Pose> poses =
        scanner::scan_poses(scanner::builtin_scene(scan.scene).scanner, [&] {
            int n = 0;
            const auto [p, ec] =
                std::from_chars(scan.poses.data(), scan.poses.data() + scan.poses.size(), n);
            if (ec != std::errc() || p != scan.poses.data() + scan.poses.size() || n < 1 || n > 20)
                throw Error(ErrorCode::kInvalidParameter,
                            cat({"--poses ", scan.poses, ": with --emulate, 1 to 20"}));
            return n;
        }());
    // The demo's own scan folder: the scans of an earlier demo go, so the new ones are 0..N-1.
    const fs::path dir = out / "scan";
    std::error_code ec;
    if (fs::is_directory(dir, ec))
        for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
            if (e.path().extension() == ".sgraw") fs::remove(e.path(), ec);
    MapConfig map_config;
    map_config.pipeline = config;
    Map map(map_config);
    for (std::size_t k = 0; k < poses.size(); ++k) {
        AcquireSettings a;
        a.emulate = scan.scene;
        a.pose = cat({std::to_string(k), "/", std::to_string(poses.size())});
        a.seed = scan.seed;
        a.out = dir.string();
        a.quiet = true;
        const AcquiredScan taken = take_scan(a);
        const PointCloud points = scanner::fuse_scans(std::span(&taken.scan, 1));
        (void)map.add_scan(points, taken.scan.pose.translation());
    }
    EmulatedDemo d{scanner::Scene(scanner::builtin_scene(scan.scene)), map.cloud(), {}};
    d.run.result = map.result();
    write_outputs(d.cloud, map.pipeline_config(), d.run.result, d.run, out, outputs, units,
                  "scan/");
    return d;
}

}  // namespace

void add_demo_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "demo",
        "Simulate the I-beam channel scan, grow surfaces, evaluate: every output in one folder");
    struct Args {
        std::string out = "demo";
        std::string poses = "3";
        GrowOptions grow;
        EvalSettings eval;
        bool emulate = false;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    // The demo runs the library's defaults (the paper's mu = 12 mm and the disk test with its
    // adaptive radius), as a user's first `surfgrow grow` would.
    cmd->add_option("-o,--out", args->out,
                    "Output folder (scan/ inside it holds the simulated scan)")
        ->capture_default_str();
    cmd->add_option("--poses", args->poses, "Scans along the channel, 0.5 m apart")
        ->capture_default_str();
    args->grow.add_to(*cmd);
    cmd->get_option("--seed")->description("Seed of the simulated noise and of the home points");
    args->eval.add_to(*cmd);
    cmd->add_flag("--emulate", args->emulate,
                  "Take the scans with the emulated URG-04LX and tilt servo behind "
                  "pseudo-terminals (surfgrow acquire --emulate) and map them scan by scan "
                  "(surfgrow map), instead of simulating and growing the fused cloud");
    cmd->add_flag("-q,--quiet", args->quiet, "Nothing on stdout");
    cmd->callback([args] {
        const CloudUnits units = args->grow.units();
        if (units.name != "m")
            throw Error(ErrorCode::kUsage, "demo: the simulated cloud is in metres (no --units)");
        PipelineConfig config;
        config.grow = args->grow.config(units);
        config.grow.progress = terminal_progress();
        const eval::EvalOptions eval_options = args->eval.options();
        const std::vector<eval::Requirement> requirements = args->eval.requirements();
        ScanSettings scan;
        scan.scene = "ibeam-channel";
        scan.poses = args->poses;
        scan.seed = args->grow.seed;

        const std::filesystem::path out(args->out);
        OutputChoice outputs;
        outputs.close_up = true;  // corner.png beside the overview, as the paper's Fig. 6
        const auto evaluate = [&](const PointCloud& cloud, const GrowRun& run,
                                  const scanner::Scene& scene) {
            const GrowResult& grown = run.result.grow;
            eval::EvalReport report = eval::evaluate(cloud, grown, scene.faces(), eval_options);
            if (run.result.planes)
                eval::add_plane_figures(
                    report, cloud, eval::GrowOutcome{grown.surfaces, grown.labels, &grown.stats},
                    *run.result.planes, scene.faces());
            return report;
        };
        GrowRun run;
        eval::EvalReport report;
        if (args->emulate) {
            const EmulatedDemo demo = emulated_demo(out, scan, config, outputs, units);
            run = demo.run;
            report = evaluate(demo.cloud, run, demo.scene);
        } else {
            const ScanData data = run_scan(scan);
            write_scan_outputs(out / "scan", data, scan);
            run = grow_and_write(data.cloud, config, out, outputs, units, "scan/cloud.ply",
                                 data.simulate_seconds + data.fuse_seconds);
            report = evaluate(data.cloud, run, *data.scene);
        }
        const GrowResult& grown = run.result.grow;
        const auto checks = eval::check_requirements(requirements, report);
        write_eval_json(out / "eval.json", report, checks);
        if (!args->quiet) {
            std::cout << summary_line(grown.stats) << "\n"
                      << eval::eval_line(report) << "\n"
                      << eval::bands_line(report) << "\n"
                      << eval::requirements_text(checks);
            std::cout.flush();
        }
        enforce(checks);
    });
}

}  // namespace surfgrow::cli
