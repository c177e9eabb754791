// surfgrow: laser-scan point clouds to oriented surface patches.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <new>

#if defined(__linux__) && defined(__GLIBC__)
#include <unistd.h>
#endif

#include "commands.hpp"
#include "exit_status.hpp"
#include "surfgrow/core/error.hpp"

namespace {

/// glibc reads its malloc tunables once, at start-up. With huge pages for the heap, a fresh
/// process takes far fewer first-touch page faults, which cost microseconds each in a virtual
/// machine: reading and growing a million-point cloud take about a third less time
/// (docs/performance.md). So the command restarts itself once with them on, unless
/// GLIBC_TUNABLES is already set (by the user, or by this restart).
void restart_with_huge_pages([[maybe_unused]] char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
    if (std::getenv("GLIBC_TUNABLES") != nullptr) return;
    if (::setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) != 0) return;
    ::execv("/proc/self/exe", argv);
    ::unsetenv("GLIBC_TUNABLES");  // no restart (no /proc?): carry on as we are
#endif
}

}  // namespace

int main(int argc, char** argv) {
    using namespace surfgrow;
    using namespace surfgrow::cli;
    restart_with_huge_pages(argv);
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
