// `surfgrow demo [-o demo]`: the README's main job. Simulates the paper's I-beam channel from a
// few poses, grows surfaces, evaluates them against the ground truth, writes everything.
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "eval_job.hpp"
#include "grow_options.hpp"
#include "grow_pipeline.hpp"
#include "scan_job.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/eval/report_text.hpp"

namespace surfgrow::cli {

void add_demo_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "demo",
        "Simulate the I-beam channel scan, grow surfaces, evaluate: every output in one folder");
    struct Args {
        std::string out = "demo";
        std::string poses = "3";
        GrowOptions grow;
        EvalSettings eval;
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
        const ScanData data = run_scan(scan);
        write_scan_outputs(out / "scan", data, scan);
        OutputChoice outputs;
        outputs.close_up = true;  // corner.png beside the overview, as the paper's Fig. 6
        const GrowRun run =
            grow_and_write(data.cloud, config, out, outputs, units, "scan/cloud.ply",
                           data.simulate_seconds + data.fuse_seconds);
        const GrowResult& grown = run.result.grow;
        eval::EvalReport report =
            eval::evaluate(data.cloud, grown, data.scene->faces(), eval_options);
        if (run.result.planes)
            eval::add_plane_figures(report, data.cloud,
                                    eval::GrowOutcome{grown.surfaces, grown.labels, &grown.stats},
                                    *run.result.planes, data.scene->faces());
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
