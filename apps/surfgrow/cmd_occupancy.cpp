// `surfgrow occupancy OUT --cloud CLOUD`: the occupancy grid and OctoMap of an existing result.
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/io/result_outputs.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::cli {

namespace {

std::string count_text(std::uint64_t n) {
    return std::to_string(n);
}

}  // namespace

void add_occupancy_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "occupancy",
        "Occupancy grid of a result: occupancy.ply, occupancy.json and an OctoMap environment.bt "
        "with free space carved from the scan origins");
    struct Args {
        std::string dir;
        std::string cloud;
        std::string viewpoint;
        bool no_octomap = false;
        int threads = 0;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("result", args->dir,
                    "Result folder of `surfgrow grow` (surfaces.json, labels.bin)")
        ->required();
    cmd->add_option("--cloud", args->cloud, "The cloud the result was grown from")->required();
    cmd->add_option("--viewpoint", args->viewpoint,
                    "Sensor position x,y,z with unit (e.g. 0,0,1.2m) to carve free space from; "
                    "default: the result's or the cloud's viewpoint");
    cmd->add_flag("--no-octomap", args->no_octomap, "Do not write environment.bt");
    add_threads_option(*cmd, args->threads, "Worker threads for the index, 0 = all cores");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args] {
        const std::filesystem::path dir = args->dir;
        const io::GrownFolder grown = io::read_grown_folder(dir, args->cloud);
        const io::StoredResult& stored = grown.result;
        const PointCloud& cloud = grown.cloud;
        const std::vector<std::int32_t>& labels = grown.labels;
        GrowerConfig config = stored.config;  // the workspace (crop, viewpoint) included
        const double metres = unit_to_metres(stored.meta.units, "surfaces.json units");
        if (!args->viewpoint.empty())
            config.viewpoint = parse_vec3_length_m(args->viewpoint, "--viewpoint") / metres;
        config.threads = args->threads;

        io::OccupancyOutputs which;
        which.octomap = !args->no_octomap;
        io::OutputTransaction tx(dir);
        const OccupancyGrid grid = occupancy_grid(cloud, labels, config);
        const io::OccupancySummary s =
            io::stage_occupancy(tx, grid, cloud, config, stored.meta, which);
        tx.commit();
        if (args->quiet) return;
        std::string line = cat({count_text(s.occupied_cubes), " occupied cubes of ",
                                format_length(config.mu * metres), " (",
                                count_text(s.registered_points), " registered points)"});
        if (s.octomap_written) {
            if (s.octomap.carving == SensorOrigins::Source::kNone)
                line += ", environment.bt without free space (no scan origin or viewpoint known)";
            else
                line += cat({", environment.bt with ", count_text(s.octomap.free),
                             " free leaves from ", count_text(s.octomap.rays), " rays (",
                             sensor_origins_name(s.octomap.carving), ")"});
        }
        std::cout << line << std::endl;
    });
}

}  // namespace surfgrow::cli
