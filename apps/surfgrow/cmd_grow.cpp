// `surfgrow grow CLOUD -o DIR`: the main job.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "grow_pipeline.hpp"
#include "grow_options.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app) {
    auto* cmd = app.add_subcommand("grow", "Grow surfaces over a point cloud (PLY, PCD, XYZ/CSV/TXT)");
    struct Args {
        std::string input;
        std::string out = "out";
        GrowOptions grow;
        OutputChoice outputs;
        bool quiet = false;
        bool stats = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("cloud", args->input, "Input cloud: .ply, .pcd, .xyz, .csv, .txt, .pts")->required();
    cmd->add_option("-o,--out", args->out, "Output folder (created; outputs replaced as a whole)")
        ->capture_default_str();
    args->grow.add_to(*cmd);
    cmd->add_flag("!--no-labels", args->outputs.labels, "Do not write labels.txt");
    cmd->add_flag("--csv", args->outputs.csv, "Also write surfaces.csv");
    cmd->add_flag("!--no-picture", args->outputs.picture, "Do not render surfaces.png");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->add_flag("--stats", args->stats, "Also print rejections and registration by range band");
    cmd->callback([args] {
        const CloudUnits units = args->grow.units();
        const auto t0 = std::chrono::steady_clock::now();
        const PointCloud cloud = io::read_cloud(args->input);
        const double read_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        GrowerConfig config = args->grow.config(units);
        config.progress = terminal_progress();
        const GrowRun run = grow_and_write(cloud, config, args->out, args->outputs, units,
                                           std::filesystem::path(args->input).filename().string(), read_s);
        if (!args->quiet) std::cout << summary_line(run.result.stats) << std::endl;
        if (args->stats) std::cout << stats_table(run.result.stats, units) << std::flush;
        if (const std::string hint = sparsity_hint(run.result.stats, config, units); !hint.empty())
            std::cerr << hint << std::endl;
    });
}

}  // namespace surfgrow::cli
