// surfgrow: laser-scan point clouds to oriented surface patches.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <memory>
#include <new>

#include "commands.hpp"
#include "exit_status.hpp"
#include "process_memory.hpp"
#include "surfgrow/core/error.hpp"

int main(int argc, char** argv) {
    using namespace surfgrow;
    using namespace surfgrow::cli;
    keep_freed_memory();
    const std::unique_ptr<CLI::App> made = make_app();
    CLI::App& app = *made;
    try {
        parse_command_line(app, argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return exit_status(ErrorCode::kUsage);
    } catch (const surfgrow::Error& e) {
        std::fprintf(stderr, "surfgrow: error: %s\n", e.what());
        return exit_status(e.code());
    } catch (const OutcomeError& e) {
        std::fprintf(stderr, "surfgrow: error: %s\n", e.what());
        return exit_status(e.outcome());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "surfgrow: error: out of memory\n");
        return exit_status(ErrorCode::kInternal);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "surfgrow: internal error: %s\n", e.what());
        return exit_status(ErrorCode::kInternal);
    }
    return 0;
}
