#include "commands.hpp"

namespace surfgrow::cli {

void add_grow_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_view_command(CLI::App& app);

void add_all_commands(CLI::App& app) {
    add_grow_command(app);
    add_render_command(app);
    add_view_command(app);
}

}  // namespace surfgrow::cli
