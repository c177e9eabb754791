#include "commands.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app);
void add_occupancy_command(CLI::App& app);
void add_collide_command(CLI::App& app);

void add_all_commands(CLI::App& app) {
    add_grow_command(app);
    add_occupancy_command(app);
    add_collide_command(app);
}

}  // namespace surfgrow::cli
