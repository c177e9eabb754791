// `surfgrow collide OUT --robot ROBOT.json`: clearance of a robot's links to the environment
// spheres of a result (paper 5.5).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "exit_status.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/collision_io.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/io/robot_file.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/robot_model.hpp"

namespace surfgrow::cli {

namespace {

std::string clearance_text(double clearance, double metres) {
    return std::isfinite(clearance) ? format_length(clearance * metres) : std::string("none");
}

}  // namespace

void add_collide_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "collide",
        "Clearance of a robot (spheres and capsules, robot.json) to a result's environment "
        "spheres; prints one line per link and writes collision.json");
    struct Args {
        std::string dir;
        std::string robot;
        std::string tolerance = "0mm";
        std::string report;
        bool fail = false;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("result", args->dir, "Result folder of `surfgrow grow` (surfaces.json)")
        ->required();
    cmd->add_option("--robot", args->robot, "Robot file (JSON: links as spheres and capsules)")
        ->required();
    cmd->add_option("--tolerance", args->tolerance,
                    "Safety margin with unit: a link collides when its clearance is below it")
        ->capture_default_str();
    cmd->add_option("--report", args->report,
                    "Where to write the report (default RESULT/collision.json)");
    cmd->add_flag("--fail-on-collision", args->fail,
                  "Exit with status 10 when a link collides (default: 0 whenever the check ran)");
    cmd->add_flag("-q,--quiet", args->quiet, "No per-link lines on stdout");
    cmd->callback([args] {
        const std::filesystem::path dir = args->dir;
        const io::StoredResult stored = io::read_result_folder(dir).result;
        const double metres = unit_to_metres(stored.meta.units, "surfaces.json units");
        const double tolerance = parse_length_m(args->tolerance, "--tolerance") / metres;
        if (tolerance < 0)
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"--tolerance must be >= 0, got ", args->tolerance}));
        const RobotModel robot = io::read_robot_json(args->robot, {metres, stored.meta.offset});
        const CollisionSpheres env = CollisionSpheres::from_surfaces(stored.surfaces);
        const std::vector<LinkClearance> results = check_robot(env, robot, tolerance);

        const std::filesystem::path report =
            args->report.empty() ? dir / "collision.json" : std::filesystem::path(args->report);
        const io::CollisionRequest request{std::filesystem::path(args->robot).filename().string(),
                                           tolerance};
        const auto write_report = [&](std::ostream& o) {
            io::write_collision_report_json(o, env, robot, results, request, stored.meta);
        };
        if (args->report.empty()) {
            // Into the result folder through its transaction: its lock, and no mix with a run
            // replacing it.
            io::OutputTransaction tx(dir);
            tx.add(report.filename().string(), write_report);
            tx.commit();
        } else {
            io::write_atomically(report, write_report);
        }

        std::size_t colliding = 0, width = 4;
        for (const RobotLink& l : robot.links) width = std::max(width, l.name.size());
        for (std::size_t i = 0; i < robot.links.size(); ++i) {
            const LinkClearance& r = results[i];
            colliding += r.collides ? 1 : 0;
            if (args->quiet) continue;
            std::string line = robot.links[i].name;
            line.resize(width + 2, ' ');
            line += cat({link_kind_name(robot.links[i].kind), "  clearance ",
                         clearance_text(r.proximity.clearance, metres),
                         r.collides ? "  COLLIDES" : "  clear"});
            if (r.proximity.nearest >= 0)
                line += cat({"  (surface ", std::to_string(r.proximity.nearest), ")"});
            std::cout << line << "\n";
        }
        if (!args->quiet) {
            std::cout << cat({std::to_string(colliding), " of ", std::to_string(robot.links.size()),
                              " links collide (tolerance ", format_length(tolerance * metres), ", ",
                              std::to_string(env.size()), " environment spheres)"})
                      << std::endl;
        }
        if (args->fail && colliding > 0)
            throw OutcomeError(
                Outcome::kCollision,
                cat({std::to_string(colliding), " of ", std::to_string(robot.links.size()),
                     " robot links are closer than ", format_length(tolerance * metres),
                     " to the environment (", report.string(), ")"}));
    });
}

}  // namespace surfgrow::cli
