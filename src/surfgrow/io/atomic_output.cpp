#include "surfgrow/io/atomic_output.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace fs = std::filesystem;

namespace {

fs::path temp_name_for(const fs::path& final_path) {
    static std::atomic<unsigned> counter{0};
    return final_path.parent_path() /
           cat({".", final_path.filename().string(), ".tmp-", std::to_string(::getpid()), "-",
                std::to_string(counter++)});
}

[[noreturn]] void cannot_write(const fs::path& path, std::string_view why) {
    throw Error(ErrorCode::kCannotWrite, cat({"cannot write ", path.string(), ": ", why}));
}

// Runs the writer into `temp`; removes `temp` and rethrows on failure.
void write_temp(const fs::path& temp, const fs::path& final_path,
                const std::function<void(std::ostream&)>& writer) {
    try {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) cannot_write(final_path, std::strerror(errno));
        writer(out);
        out.flush();
        if (!out) cannot_write(final_path, "write failed (disk full?)");
        out.close();
        if (out.fail()) cannot_write(final_path, "close failed (disk full?)");
    } catch (...) {
        std::error_code ec;
        fs::remove(temp, ec);
        throw;
    }
}

}  // namespace

void write_atomically(const fs::path& path, const std::function<void(std::ostream&)>& writer) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(parent, ec)) cannot_write(path, "its folder does not exist");
    const fs::path temp = temp_name_for(path.has_parent_path() ? path : fs::path(".") / path);
    write_temp(temp, path, writer);
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        cannot_write(path, ec.message());
    }
}

OutputTransaction::OutputTransaction(fs::path dir) : dir_(std::move(dir)) {
    std::error_code ec;
    if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
        cannot_write(dir_, "it exists and is not a folder");
    fs::create_directories(dir_, ec);
    if (ec) cannot_write(dir_, ec.message());
}

OutputTransaction::~OutputTransaction() {
    if (committed_) return;
    for (const Staged& s : staged_) {
        std::error_code ec;
        fs::remove(s.temp, ec);
    }
}

void OutputTransaction::add(const std::string& name,
                            const std::function<void(std::ostream&)>& writer) {
    const fs::path final_path = dir_ / name;
    const fs::path temp = temp_name_for(final_path);
    write_temp(temp, final_path, writer);
    staged_.push_back({temp, final_path});
}

std::vector<fs::path> OutputTransaction::files() const {
    std::vector<fs::path> out;
    for (const Staged& s : staged_) out.push_back(s.final_path);
    return out;
}

void OutputTransaction::commit() {
    for (const Staged& s : staged_) {
        std::error_code ec;
        fs::rename(s.temp, s.final_path, ec);
        if (ec) cannot_write(s.final_path, ec.message());
    }
    committed_ = true;
}

}  // namespace surfgrow::io
