// `surfgrow planes DIR --cloud CLOUD`: bound planes of an existing result.
#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "planes_options.hpp"
#include "surfaces_picture.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/io/result_outputs.hpp"

namespace surfgrow::cli {

void add_planes_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "planes", "Merge a result's surfaces into bound planes: planes.json and planes.ply");
    struct Args {
        std::string dir;
        std::string cloud;
        PlanesOptions planes;
        int threads = 0;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("dir", args->dir, "Result folder written by `surfgrow grow`")->required();
    cmd->add_option("--cloud", args->cloud, "The cloud the result was grown from")->required();
    args->planes.add_to(*cmd);
    add_threads_option(*cmd, args->threads, "Worker threads, 0 = all cores");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args] {
        const io::GrownFolder f = io::read_grown_folder(args->dir, args->cloud);
        const io::ResultMeta& meta = f.result.meta;
        const BoundPlaneConfig config =
            args->planes.config(unit_to_metres(meta.units, "units in surfaces.json"),
                                f.result.config.mu, args->threads);
        const BoundPlanes planes =
            compute_bound_planes(f.cloud, f.result.surfaces, f.labels, config);
        io::OutputTransaction tx(args->dir);
        io::stage_planes(tx, planes, meta, args->planes.obj);
        // The pictures grow drew are coloured by plane: drawn again with the new planes.
        const std::filesystem::path dir(args->dir);
        stage_surfaces_pictures(tx, f.result.surfaces, f.result.stats, planes.plane_of_patch,
                                meta.units, args->threads,
                                std::filesystem::exists(dir / "surfaces.png"),
                                std::filesystem::exists(dir / "corner.png"));
        tx.commit();
        if (!tx.removed().empty()) {
            std::string names;
            for (const std::string& n : tx.removed()) names += (names.empty() ? "" : ", ") + n;
            std::cerr << "surfgrow: note: removed " << names
                      << " (made from the previous planes); run `surfgrow coverage` or `eval` "
                         "again for new ones"
                      << std::endl;
        }
        if (!args->quiet) std::cout << planes_summary(planes, meta.units) << std::endl;
    });
}

}  // namespace surfgrow::cli
