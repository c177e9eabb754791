#include "surfgrow/io/atomic_output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void cannot_write(const fs::path& path, std::string_view why) {
    throw Error(ErrorCode::kCannotWrite, cat({"cannot write ", path.string(), ": ", why}));
}

std::string errno_text() {
    return std::strerror(errno);
}

// fsync of a file or a folder by path. Folders on some file systems refuse fsync (EINVAL): their
// entries are then as durable as that file system makes them.
void sync_path(const fs::path& path, const fs::path& named) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) cannot_write(named, cat({"cannot sync ", path.string(), ": ", errno_text()}));
    const bool ok = ::fsync(fd) == 0 || errno == EINVAL;
    const std::string why = ok ? "" : errno_text();
    ::close(fd);
    if (!ok) cannot_write(named, cat({"cannot sync it to disk: ", why}));
}

// Starts the kernel's write-back of a finished file, so the fsync at commit mostly waits for
// nothing: the files of a result are written back in parallel with staging the next ones.
void start_writeback(const fs::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);
    ::close(fd);
}

// Runs the writer into `temp`; removes `temp` and rethrows on failure.
void write_file(const fs::path& temp, const fs::path& final_path,
                const std::function<void(std::ostream&)>& writer) {
    try {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) cannot_write(final_path, errno_text());
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

// `.NAME.tmp-PID-N`: write_atomically's temporary for NAME. Returns the PID, or 0 if `entry` is
// not such a name (for `name`, or for any NAME when `name` is empty).
long temp_owner(std::string_view entry, std::string_view name) {
    if (entry.size() < 2 || entry[0] != '.') return 0;
    const std::size_t tag = entry.rfind(".tmp-");
    if (tag == std::string_view::npos || tag < 2) return 0;
    if (!name.empty() && entry.substr(1, tag - 1) != name) return 0;
    const std::string_view rest = entry.substr(tag + 5);
    const std::size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string_view::npos || dash + 1 == rest.size()) return 0;
    if (!std::all_of(rest.begin(), rest.end(),
                     [](char c) { return c == '-' || (c >= '0' && c <= '9'); }))
        return 0;
    return std::stol(std::string(rest.substr(0, dash)));
}

bool process_is_gone(long pid) {
    return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

fs::path temp_name_for(const fs::path& final_path) {
    static std::atomic<unsigned> counter{0};
    return final_path.parent_path() /
           cat({".", final_path.filename().string(), ".tmp-", std::to_string(::getpid()), "-",
                std::to_string(counter++)});
}

// `dir` as an absolute path with symlinks resolved and no trailing separator: the folder a
// commit replaces (a symlink to a result folder keeps pointing at the new result).
fs::path resolve_folder(const fs::path& dir) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(dir, ec), ec);
    if (ec) p = fs::absolute(dir, ec).lexically_normal();
    while (!p.has_filename() && p.has_relative_path()) p = p.parent_path();
    return p;
}

bool is_mount_point(const fs::path& dir) {
    struct stat self {
    }, parent{};
    if (::stat(dir.c_str(), &self) != 0 || ::stat(dir.parent_path().c_str(), &parent) != 0)
        return false;
    return self.st_dev != parent.st_dev;
}

std::string sibling(const fs::path& target, std::string_view kind) {
    return cat({".", target.filename().string(), ".", kind, "-"});
}

bool starts_with(std::string_view s, std::string_view prefix) {
    return s.substr(0, prefix.size()) == prefix;
}

}  // namespace

void write_atomically(const fs::path& path, const std::function<void(std::ostream&)>& writer) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(parent, ec)) cannot_write(path, "its folder does not exist");
    const fs::path temp = temp_name_for(parent / path.filename());
    write_file(temp, path, writer);
    try {
        sync_path(temp, path);
    } catch (...) {
        fs::remove(temp, ec);
        throw;
    }
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        cannot_write(path, ec.message());
    }
    sync_path(parent, path);
    // Temporaries of this file left by killed runs (their process is gone).
    const std::string name = path.filename().string();
    for (const fs::directory_entry& e : fs::directory_iterator(parent, ec)) {
        const long pid = temp_owner(e.path().filename().string(), name);
        if (pid > 0 && process_is_gone(pid)) fs::remove(e.path(), ec);
    }
}

OutputTransaction::OutputTransaction(fs::path dir, PreviousOutputs previous)
    : dir_(std::move(dir)), target_(resolve_folder(dir_)), previous_(std::move(previous)) {
    std::error_code ec;
    if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
        cannot_write(dir_, "it exists and is not a folder");
    if (!target_.has_filename() || target_ == target_.root_path())
        cannot_write(dir_, "a file system's root cannot be replaced; write into a folder in it");
    const fs::path parent = target_.parent_path();
    fs::create_directories(parent, ec);
    if (ec) cannot_write(dir_, ec.message());
    if (fs::exists(target_, ec) && is_mount_point(target_))
        cannot_write(dir_,
                     "it is a mount point, which cannot be replaced atomically; write into a "
                     "folder inside it");
    lock_ = std::make_unique<FolderLock>(target_);

    // What a killed run left beside the folder. Between the two renames of the fallback commit
    // (no RENAME_EXCHANGE) the old folder sits aside as .NAME.old-PID: put it back first.
    const std::string staging_tag = sibling(target_, "staging"), old_tag = sibling(target_, "old");
    std::vector<fs::path> leftovers;
    for (const fs::directory_entry& e : fs::directory_iterator(parent, ec)) {
        const std::string name = e.path().filename().string();
        if (starts_with(name, staging_tag) || starts_with(name, old_tag))
            leftovers.push_back(e.path());
    }
    std::sort(leftovers.begin(), leftovers.end());
    for (const fs::path& p : leftovers)
        if (starts_with(p.filename().string(), old_tag) && !fs::exists(target_, ec))
            fs::rename(p, target_, ec);
    for (const fs::path& p : leftovers) fs::remove_all(p, ec);

    staging_ = parent / cat({staging_tag, std::to_string(::getpid())});
    fs::create_directory(staging_, ec);
    if (ec) cannot_write(dir_, cat({"cannot create ", staging_.string(), ": ", ec.message()}));
}

OutputTransaction::~OutputTransaction() {
    if (committed_) return;
    std::error_code ec;
    fs::remove_all(staging_, ec);
}

void OutputTransaction::add(const std::string& name,
                            const std::function<void(std::ostream&)>& writer) {
    const fs::path file = staging_ / name;
    write_file(file, dir_ / name, writer);
    start_writeback(file);
    if (std::find(staged_.begin(), staged_.end(), name) == staged_.end()) staged_.push_back(name);
}

void OutputTransaction::drop(const std::string& name) {
    dropped_.push_back(name);
}

std::vector<fs::path> OutputTransaction::files() const {
    std::vector<fs::path> out;
    for (const std::string& s : staged_) out.push_back(dir_ / s);
    return out;
}

bool OutputTransaction::keeps(const std::string& name) const {
    if (std::find(staged_.begin(), staged_.end(), name) != staged_.end()) return false;
    if (std::find(dropped_.begin(), dropped_.end(), name) != dropped_.end()) return false;
    if (previous_ && previous_(name)) return false;
    // Temporaries of earlier versions' per-file commits, killed half way.
    const long pid = temp_owner(name, "");
    return !(pid > 0 && process_is_gone(pid));
}

// Hard links of the old folder's kept entries in the staging folder (copies where the file
// system has no hard links): the old folder stays whole until the swap.
void OutputTransaction::carry_over() {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(target_, ec)) {
        const std::string name = e.path().filename().string();
        if (!keeps(name)) {
            if (std::find(staged_.begin(), staged_.end(), name) == staged_.end())
                removed_.push_back(name);
            continue;
        }
        const fs::path to = staging_ / name;
        std::error_code link_ec;
        if (e.is_symlink(link_ec))
            fs::copy_symlink(e.path(), to, link_ec);
        else
            fs::copy(e.path(), to,
                     fs::copy_options::recursive | fs::copy_options::create_hard_links, link_ec);
        if (link_ec) {
            link_ec.clear();
            fs::remove_all(to, link_ec);
            fs::copy(e.path(), to, fs::copy_options::recursive, link_ec);
        }
        if (link_ec)
            cannot_write(dir_, cat({"cannot keep ", e.path().string(),
                                    " in the new result: ", link_ec.message()}));
    }
    if (ec) cannot_write(dir_, cat({"cannot list it: ", ec.message()}));
    std::sort(removed_.begin(), removed_.end());
}

void OutputTransaction::commit() {
    std::error_code ec;
    const fs::path parent = target_.parent_path();
    const bool exists = fs::exists(target_, ec);
    if (exists) carry_over();
    for (const std::string& name : staged_) sync_path(staging_ / name, dir_ / name);
    sync_path(staging_, dir_);

    if (!exists) {
        if (std::rename(staging_.c_str(), target_.c_str()) != 0) cannot_write(dir_, errno_text());
    } else if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(),
                           RENAME_EXCHANGE) == 0) {
        committed_ = true;  // staging_ now holds the old content, removed below
    } else if (errno == EINVAL || errno == ENOSYS || errno == EOPNOTSUPP) {
        // No atomic exchange on this file system: move the old folder aside, the new one in.
        // A run killed in between leaves .NAME.old-PID, which the next run puts back.
        const fs::path old = parent / cat({sibling(target_, "old"), std::to_string(::getpid())});
        if (std::rename(target_.c_str(), old.c_str()) != 0) cannot_write(dir_, errno_text());
        if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
            const std::string why = errno_text();
            (void)std::rename(old.c_str(), target_.c_str());
            cannot_write(dir_, why);
        }
        staging_ = old;
    } else {
        cannot_write(dir_, cat({"cannot replace it: ", errno_text()}));
    }
    committed_ = true;
    sync_path(parent, dir_);
    if (exists) fs::remove_all(staging_, ec);  // the old result
    lock_.reset();                             // published: the next run may go ahead
}

}  // namespace surfgrow::io
