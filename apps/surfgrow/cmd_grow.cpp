// `surfgrow grow CLOUD -o DIR`: the main job.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "coverage_options.hpp"
#include "grow_options.hpp"
#include "grow_pipeline.hpp"
#include "planes_options.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app) {
    auto* cmd =
        app.add_subcommand("grow", "Grow surfaces over a point cloud (PLY, PCD, XYZ/CSV/TXT)");
    struct Args {
        std::string input;
        std::string out = "out";
        GrowOptions grow;
        OutputChoice outputs;
        PlanesOptions planes;
        CoverageOptions coverage;
        bool no_planes = false;
        bool no_coverage = false;
        bool quiet = false;
        bool stats = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("cloud", args->input, "Input cloud: .ply, .pcd, .xyz, .csv, .txt, .pts")
        ->required();
    cmd->add_option("-o,--out", args->out, "Output folder (created; outputs replaced as a whole)")
        ->capture_default_str();
    args->grow.add_to(*cmd);
    cmd->add_flag("!--no-labels", args->outputs.labels, "Do not write labels.txt");
    cmd->add_flag("--csv", args->outputs.csv, "Also write surfaces.csv");
    cmd->add_flag("!--no-picture", args->outputs.picture, "Do not render surfaces.png");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->add_flag("--stats", args->stats,
                  "Also print rejections, registration by range band and the robot outputs");
    // The robot outputs (each also has its own subcommand that works on an existing result).
    auto* robot = cmd->add_option_group("Robot outputs", "Written next to the surfaces by default");
    robot->add_flag("--no-planes", args->no_planes,
                    "Do not write planes.json/planes.ply (nor coverage, which needs them)");
    robot->add_flag("--no-coverage", args->no_coverage, "Do not write coverage.json/coverage.csv");
    robot->add_flag("!--no-occupancy", args->outputs.occupancy,
                    "Do not write occupancy.ply/occupancy.json");
    robot->add_flag("!--no-octomap", args->outputs.octomap, "Do not write environment.bt");
    robot->add_flag("!--no-collision", args->outputs.collision,
                    "Do not write collision_spheres.json");
    args->planes.add_to(*cmd->add_option_group("Bound planes (planes.json, planes.ply)"));
    args->coverage.add_to(*cmd->add_option_group("Coverage (coverage.json, coverage.csv)"));
    cmd->callback([args] {
        const CloudUnits units = args->grow.units();
        const auto t0 = std::chrono::steady_clock::now();
        const PointCloud cloud = io::read_cloud(args->input);
        const double read_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        GrowerConfig config = args->grow.config(units);
        // --start is in file coordinates: the cloud's offset moves it into the grower's frame.
        args->outputs.planes.reset();
        args->outputs.coverage.reset();
        if (!args->no_planes) {
            args->outputs.planes = args->planes.config(units.metres, config.mu, config.threads);
            args->outputs.planes_obj = args->planes.obj;
            if (!args->no_coverage)
                args->outputs.coverage =
                    args->coverage.config(units.metres, cloud.offset, config.threads);
        }
        config.progress = terminal_progress();
        const GrowRun run =
            grow_and_write(cloud, config, args->out, args->outputs, units,
                           std::filesystem::path(args->input).filename().string(), read_s);
        if (!args->quiet) std::cout << summary_line(run.result.stats) << std::endl;
        if (args->stats) {
            std::cout << stats_table(run.result.stats, units);
            for (const std::string* line :
                 {&run.robot.planes, &run.robot.coverage, &run.robot.occupancy})
                if (!line->empty()) std::cout << *line << "\n";
            std::cout << std::flush;
        }
        if (const std::string hint = sparsity_hint(run.result.stats, config, units); !hint.empty())
            std::cerr << hint << std::endl;
    });
}

}  // namespace surfgrow::cli
