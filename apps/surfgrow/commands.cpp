#include "commands.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app);
void add_scan_command(CLI::App& app);
void add_scan2cloud_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_demo_command(CLI::App& app);

void add_all_commands(CLI::App& app) {
    add_grow_command(app);
    add_scan_command(app);
    add_scan2cloud_command(app);
    add_eval_command(app);
    add_demo_command(app);
}

}  // namespace surfgrow::cli
