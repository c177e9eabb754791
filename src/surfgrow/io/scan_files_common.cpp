#include "surfgrow/io/scan_files_common.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "surfgrow/core/memory_budget.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io::detail {

namespace fs = std::filesystem;

std::string read_file_capped(const fs::path& path, std::size_t max_bytes, std::string_view what) {
    const std::string name = path.string();
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw Error(ErrorCode::kCannotOpen, cat({"cannot open ", name, ": it is a folder"}));
    const auto size = fs::file_size(path, ec);
    if (ec) throw Error(ErrorCode::kCannotOpen, cat({"cannot open ", name, ": ", ec.message()}));
    if (size > max_bytes)
        malformed(name, cat({"too large for ", what, " (", std::to_string(size), " bytes, at most ",
                             std::to_string(max_bytes), ")"}));
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(ErrorCode::kCannotOpen,
                    cat({"cannot open ", name, ": ", std::strerror(errno)}));
    std::string bytes(static_cast<std::size_t>(size), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::uintmax_t>(in.gcount()) != size)
        throw Error(ErrorCode::kCannotOpen, cat({"cannot read ", name, ": short read"}));
    return bytes;
}

void rethrow_in(std::string_view name, const Error& e) {
    throw Error(e.code(), cat({name, ": ", e.what()}));
}

void malformed(std::string_view name, std::string_view message) {
    throw Error(ErrorCode::kMalformedInput, cat({name, ": ", message}));
}

void check_json_limits(std::string_view text, std::string_view name, int max_depth) {
    // nlohmann::json holds a document in about 4 to 6 times its text (measured: 21 MB of
    // surfaces.json take 100 MB); plan for 6.
    check_memory(
        6.0 * double(text.size()),
        cat({name, ": parsing its ", std::to_string(text.size() / 1000000), " MB of JSON"}));
    int depth = 0;
    bool in_string = false, escaped = false;
    for (const char c : text) {
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
            continue;
        }
        if (c == '"')
            in_string = true;
        else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                malformed(name,
                          cat({"JSON nested deeper than ", std::to_string(max_depth), " levels"}));
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

}  // namespace surfgrow::io::detail
