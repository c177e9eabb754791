// The CLI's subcommands. Each lives in its own cmd_<name>.cpp and registers itself on the app.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>

namespace surfgrow::cli {

/// Adds every subcommand to `app`. A subcommand's callback throws surfgrow::Error on failure.
void add_all_commands(CLI::App& app);

/// The whole command line as main() parses it: one subcommand required, --version, every
/// subcommand (add_all_commands). fuzz/cli_args.cpp parses with the same definition.
[[nodiscard]] std::unique_ptr<CLI::App> make_app();

}  // namespace surfgrow::cli
