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

/// app.parse(argc, argv), refusing an empty argument first (CLI::ValidationError, exit 2): CLI11
/// 2.1 takes "" for the name of a nameless option group (grow's output groups) and then loops
/// forever on an unknown short flag (`grow x "" -ht`, found by fuzz/cli_args). A flag's value
/// beyond 64 bits (`--csv=99999999999999999999`), which CLI11 lets out as std::out_of_range, is
/// a usage error too (command_line.cpp, on its own: see there).
void parse_command_line(CLI::App& app, int argc, const char* const* argv);

}  // namespace surfgrow::cli
