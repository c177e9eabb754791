#include "commands.hpp"

#include <string>

#include "surfgrow/version.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app);
void add_planes_command(CLI::App& app);
void add_coverage_command(CLI::App& app);
void add_occupancy_command(CLI::App& app);
void add_collide_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_scan_command(CLI::App& app);
void add_scan2cloud_command(CLI::App& app);
void add_acquire_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_map_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_study_command(CLI::App& app);

// The order here is the order of `surfgrow --help`: the main job first, then what is made from
// its result, then the simulator and evaluation.
void add_all_commands(CLI::App& app) {
    add_grow_command(app);
    add_planes_command(app);
    add_coverage_command(app);
    add_occupancy_command(app);
    add_collide_command(app);
    add_render_command(app);
    add_view_command(app);
    add_scan_command(app);
    add_scan2cloud_command(app);
    add_acquire_command(app);
    add_calibrate_command(app);
    add_map_command(app);
    add_eval_command(app);
    add_demo_command(app);
    add_sweep_command(app);
    add_study_command(app);
}

std::unique_ptr<CLI::App> make_app() {
    auto app = std::make_unique<CLI::App>(
        "surfgrow: laser-scan point clouds to oriented surface patches (Paul, Liu, Kirchner)");
    app->require_subcommand(1);
    app->set_version_flag("--version", "surfgrow " SURFGROW_VERSION);
    add_all_commands(*app);
    return app;
}

}  // namespace surfgrow::cli
