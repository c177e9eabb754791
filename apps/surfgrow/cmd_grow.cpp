// `surfgrow grow CLOUD -o DIR`: the main job.
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "coverage_options.hpp"
#include "grow_options.hpp"
#include "grow_pipeline.hpp"
#include "planes_options.hpp"
#include "surfgrow/core/stopwatch.hpp"
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
        bool collision = true;
        bool quiet = false;
        bool stats = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("cloud", args->input, "Input cloud: .ply, .pcd, .xyz, .csv, .txt, .pts")
        ->required();
    cmd->add_option("-o,--out", args->out, "Output folder (created; outputs replaced as a whole)")
        ->capture_default_str();
    args->grow.add_to(*cmd);
    cmd->add_flag("!--no-labels", args->outputs.files.labels, "Do not write labels.bin");
    cmd->add_flag("--labels-txt", args->outputs.files.labels_txt,
                  "Also write labels.txt (the labels as text, one per line)");
    cmd->add_flag("--csv", args->outputs.files.csv, "Also write surfaces.csv");
    cmd->add_flag("!--no-picture", args->outputs.picture, "Do not render surfaces.png");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->add_flag("--stats", args->stats,
                  "Also print rejections, registration by range band and the robot outputs");
    // The robot outputs (each also has its own subcommand that works on an existing result).
    auto* robot = cmd->add_option_group("Robot outputs", "Written next to the surfaces by default");
    robot->add_flag("--no-planes", args->no_planes,
                    "Do not write planes.json/planes.ply (nor coverage, which needs them)");
    robot->add_flag("--no-coverage", args->no_coverage, "Do not write coverage.json/coverage.ply");
    robot->add_flag("!--no-occupancy", args->outputs.files.occupancy,
                    "Do not write occupancy.ply/occupancy.json");
    robot->add_flag("!--no-octomap", args->outputs.files.octomap, "Do not write environment.bt");
    robot->add_flag("!--no-collision", args->collision,
                    "Do not write collision_spheres.json and collision_spheres.ply");
    args->planes.add_to(*cmd->add_option_group("Bound planes (planes.json, planes.ply)"));
    args->coverage.add_to(*cmd->add_option_group("Coverage (coverage.json, coverage.ply)"));
    cmd->callback([args] {
        const CloudUnits units = args->grow.units();
        const Stopwatch read;
        const PointCloud cloud = io::read_cloud(args->input, io::kPointsOnly);
        const double read_s = read.seconds();
        PipelineConfig config;
        config.grow = args->grow.config(units);
        config.planes.reset();
        config.coverage.reset();
        if (!args->no_planes) {
            config.planes = args->planes.config(units.metres, config.grow.mu, config.grow.threads);
            args->outputs.files.planes_obj = args->planes.obj;
            args->outputs.files.coverage_csv = args->coverage.csv;
            // --start is in file coordinates: the cloud's offset moves it into the grower's frame.
            if (!args->no_coverage)
                config.coverage =
                    args->coverage.config(units.metres, cloud.offset, config.grow.threads);
        }
        config.occupancy = args->outputs.files.occupancy || args->outputs.files.octomap;
        config.collision = args->collision;
        config.grow.progress = terminal_progress();
        const GrowRun run =
            grow_and_write(cloud, config, args->out, args->outputs, units,
                           std::filesystem::path(args->input).filename().string(), read_s);
        if (!args->quiet) std::cout << summary_line(run.result.grow.stats) << std::endl;
        if (args->stats) {
            std::cout << stats_table(run.result.grow.stats, units);
            for (const std::string* line :
                 {&run.robot.planes, &run.robot.coverage, &run.robot.occupancy})
                if (!line->empty()) std::cout << *line << "\n";
            std::cout << std::flush;
        }
        if (const std::string hint = sparsity_hint(run.result.grow.stats, config.grow, units);
            !hint.empty())
            std::cerr << hint << std::endl;
        if (const std::string hint = orientation_hint(run.result.grow.stats); !hint.empty())
            std::cerr << hint << std::endl;
    });
}

}  // namespace surfgrow::cli
