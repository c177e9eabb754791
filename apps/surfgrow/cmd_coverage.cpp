// `surfgrow coverage DIR`: goals, approach poses and a path over the bound planes of a result.
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "coverage_options.hpp"
#include "planes_options.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/io/result_outputs.hpp"

namespace surfgrow::cli {

void add_coverage_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "coverage",
        "Goals, approach poses and a path over a result's bound planes: coverage.json/ply");
    struct Args {
        std::string dir;
        std::string cloud;
        CoverageOptions coverage;
        int threads = 0;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("dir", args->dir, "Result folder (with planes.json, or give --cloud)")
        ->required();
    cmd->add_option("--cloud", args->cloud,
                    "The cloud the result was grown from: computes planes.json (default "
                    "parameters) when the folder has none");
    args->coverage.add_to(*cmd);
    add_threads_option(*cmd, args->threads, "Worker threads, 0 = all cores");
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args] {
        namespace fs = std::filesystem;
        const fs::path dir = args->dir;
        const io::StoredResult result = io::read_grown_result(dir);
        const double metres = unit_to_metres(result.meta.units, "units in surfaces.json");
        const CoverageConfig config =
            args->coverage.config(metres, result.meta.offset, args->threads);

        io::OutputTransaction tx(dir);
        BoundPlanes planes;
        std::error_code ec;
        if (fs::exists(dir / "planes.json", ec)) {
            io::StoredPlanes stored = io::read_planes_json(dir / "planes.json");
            io::check_derived_file(dir / "planes.json", stored.meta, stored.planes.stats.patches,
                                   result, "run `surfgrow planes` again");
            planes = std::move(stored.planes);
        } else if (!args->cloud.empty()) {
            const io::GrownFolder f = io::read_grown_folder(dir, args->cloud);
            planes = compute_bound_planes(
                f.cloud, f.result.surfaces, f.labels,
                PlanesOptions{}.config(metres, f.result.config.mu, args->threads));
            io::stage_planes(tx, planes, result.meta, false);
        } else {
            throw Error(ErrorCode::kCannotOpen,
                        cat({(dir / "planes.json").string(), " is missing: run `surfgrow planes ",
                             dir.string(), " --cloud CLOUD` first, or give --cloud"}));
        }
        const CoveragePlan plan = plan_coverage(planes, result.surfaces, config);
        io::stage_coverage(tx, plan, result.meta, args->coverage.csv);
        tx.commit();
        if (!args->quiet) std::cout << coverage_summary(plan, result.meta.units) << std::endl;
    });
}

}  // namespace surfgrow::cli
