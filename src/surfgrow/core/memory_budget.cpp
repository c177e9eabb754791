#include "surfgrow/core/memory_budget.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

namespace {

constexpr const char* kVariable = "SURFGROW_MEMORY_LIMIT";

std::uint64_t physical_memory() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page <= 0) return UINT64_MAX;  // unknown: no limit of our own
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
}

std::string megabytes(double bytes) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
    return buf;
}

}  // namespace

std::uint64_t memory_budget() {
    const char* set = std::getenv(kVariable);
    if (set == nullptr || *set == '\0') return physical_memory();
    const std::string text(set);
    std::size_t end = 0;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    double scale = 1;
    if (end + 1 == text.size()) {
        switch (std::toupper(static_cast<unsigned char>(text[end]))) {
            case 'K':
                scale = 1024.0;
                break;
            case 'M':
                scale = 1024.0 * 1024;
                break;
            case 'G':
                scale = 1024.0 * 1024 * 1024;
                break;
            case 'T':
                scale = 1024.0 * 1024 * 1024 * 1024;
                break;
            default:
                scale = 0;
        }
    } else if (end != text.size()) {
        scale = 0;
    }
    if (end == 0 || end > 15 || scale == 0)
        throw Error(ErrorCode::kUsage,
                    cat({kVariable, "='", text,
                         "' is not a size: bytes, with an optional K, M, G or T (e.g. 8G)"}));
    return static_cast<std::uint64_t>(std::stod(text.substr(0, end)) * scale);
}

void check_memory(double bytes, std::string_view what) {
    const std::uint64_t budget = memory_budget();
    if (!(bytes > double(budget))) return;
    const bool limited = std::getenv(kVariable) != nullptr && *std::getenv(kVariable) != '\0';
    throw Error(ErrorCode::kCloudTooLarge,
                cat({std::string(what), " needs about ", megabytes(bytes),
                     " of memory, more than the ", megabytes(double(budget)),
                     limited ? cat({" ", kVariable, " allows"}) : std::string(" this machine has"),
                     "; crop the workspace or split the input"}));
}

}  // namespace surfgrow
