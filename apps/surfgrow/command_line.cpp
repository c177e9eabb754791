// parse_command_line, in a file of its own: its catch, compiled in a unity batch beside the
// command files' CLI11 validators, made GCC 12 report a false -Wnull-dereference in CLI11.
#include "commands.hpp"

#include <stdexcept>
#include <string>

namespace surfgrow::cli {

void parse_command_line(CLI::App& app, int argc, const char* const* argv) {
    for (int i = 1; i < argc; ++i)
        if (argv[i][0] == '\0')
            throw CLI::ValidationError(
                "argument " + std::to_string(i) +
                " is empty: leave it out (an option's value cannot be empty)");
    try {
        app.parse(argc, argv);
    } catch (const std::out_of_range&) {
        // CLI11 2.1 reads a flag's value ("--csv=7") with std::stoll and lets a number beyond 64
        // bits escape as std::out_of_range (found by fuzz/cli_args): a usage error like any other.
        throw CLI::ValidationError(
            "a flag's value is out of range: a flag takes no value, true/false or a whole number");
    }
}

}  // namespace surfgrow::cli
