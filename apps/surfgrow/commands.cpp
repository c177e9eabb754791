#include "commands.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app);
void add_planes_command(CLI::App& app);
void add_coverage_command(CLI::App& app);

void add_all_commands(CLI::App& app) {
    add_grow_command(app);
    add_planes_command(app);
    add_coverage_command(app);
}

}  // namespace surfgrow::cli
