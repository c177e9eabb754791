// Fuzzes the command line: the input, split at NUL bytes, is argv after "surfgrow", parsed by the
// real CLI11 definition (cli::make_app, as main() uses). The top app's parse-complete callback,
// which CLI11 runs after every option has been parsed, checked and converted and before any
// subcommand's callback, throws: so the parse is the real one, but no command does its work
// (reading clouds, writing results). (Replacing the subcommands' callbacks instead would free the
// option variables their lambdas own.) Each argument then also goes through the value syntax the
// commands use in their callbacks: lengths with units, vectors, units.
//
// Expected answers: CLI::Error (a parse error, --help, --version) and surfgrow::Error. Anything
// else escaping (std::out_of_range from a conversion, ...) is a finding.
//
// The definition is built once and cleared (CLI::App::clear) between inputs: building it takes
// about 10 ms under ASan, the parse a few microseconds. The options' variables keep what an
// earlier input set (main parses once, from their defaults), so a finding is confirmed by the
// replay, which builds a fresh definition for each input (SURFGROW_FUZZ_FRESH_APP, set by
// replay_main.cpp).
#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "surfgrow/core/error.hpp"

namespace {

struct Parsed {};  // thrown once the command line is parsed, before the command runs

template <class F>
void expect_error_or_value(F&& f) {
    try {
        (void)f();
    } catch (const surfgrow::Error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfgrow::cli;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> args{"surfgrow"};
    std::size_t start = 0;
    while (start <= bytes.size() && size > 0) {
        const std::size_t nul = bytes.find('\0', start);
        args.emplace_back(bytes.substr(start, nul - start));
        if (nul == std::string_view::npos) break;
        start = nul + 1;
    }
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    static std::unique_ptr<CLI::App> reused;
    std::unique_ptr<CLI::App> fresh;
    const bool each_input = std::getenv("SURFGROW_FUZZ_FRESH_APP") != nullptr;
    std::unique_ptr<CLI::App>& app = each_input ? fresh : reused;
    if (!app) {
        app = make_app();
        app->parse_complete_callback([] { throw Parsed{}; });
    } else {
        app->clear();
    }
    try {
        parse_command_line(*app, static_cast<int>(args.size()), argv.data());
    } catch (const Parsed&) {
    } catch (const CLI::Error&) {
    } catch (const surfgrow::Error&) {
    }

    // The last argument also goes through the value parsers. One is enough (the mutations reach
    // every argument in turn); every argument took five exceptions each, most of the time.
    if (args.size() > 1) {
        const std::string_view a = args.back();
        expect_error_or_value([&] { return parse_length_m(a, "--fuzz"); });
        expect_error_or_value([&] { return unit_to_metres(a, "--fuzz"); });
        expect_error_or_value([&] { return parse_vec3(a, "--fuzz"); });
        expect_error_or_value([&] { return parse_vec3_length_m(a, "--fuzz"); });
        expect_error_or_value([&] { return parse_lengths_m(a, "--fuzz", 6); });
    }
    return 0;
}
