#include "commands.hpp"

namespace surfgrow::cli {

void add_all_commands(CLI::App& app) {
    (void)app;
}

}  // namespace surfgrow::cli
