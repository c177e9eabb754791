// surfgrow: laser-scan point clouds to oriented surface patches.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <new>

#include "commands.hpp"
#include "surfgrow/core/error.hpp"

int main(int argc, char** argv) {
    CLI::App app{
        "surfgrow: laser-scan point clouds to oriented surface patches (Paul, Liu, Kirchner)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "surfgrow " SURFGROW_VERSION);
    surfgrow::cli::add_all_commands(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return static_cast<int>(surfgrow::ErrorCode::kUsage);
    } catch (const surfgrow::Error& e) {
        std::fprintf(stderr, "surfgrow: error: %s\n", e.what());
        return e.exit_code();
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "surfgrow: error: out of memory\n");
        return static_cast<int>(surfgrow::ErrorCode::kInternal);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "surfgrow: internal error: %s\n", e.what());
        return static_cast<int>(surfgrow::ErrorCode::kInternal);
    }
    return 0;
}
