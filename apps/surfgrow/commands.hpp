// The CLI's subcommands. Each lives in its own cmd_<name>.cpp and registers itself on the app.
#pragma once

#include <CLI/CLI.hpp>

namespace surfgrow::cli {

/// Adds every subcommand to `app`. A subcommand's callback throws surfgrow::Error on failure.
void add_all_commands(CLI::App& app);

}  // namespace surfgrow::cli
