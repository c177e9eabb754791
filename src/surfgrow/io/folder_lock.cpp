#include "surfgrow/io/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace fs = std::filesystem;

FolderLock::FolderLock(const fs::path& folder) {
    const fs::path file = folder.parent_path() / cat({".", folder.filename().string(), ".lock"});
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
        throw Error(ErrorCode::kCannotWrite,
                    cat({"cannot write ", folder.string(), ": cannot create its lock file ",
                         file.string(), ": ", std::strerror(errno)}));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        // The holder wrote its pid; name it so the user knows what to wait for.
        char pid[32] = {};
        const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
        ::close(fd_);
        fd_ = -1;
        std::string holder = n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : "";
        while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' '))
            holder.pop_back();
        throw Error(ErrorCode::kCannotWrite,
                    cat({"cannot write ", folder.string(), ": another surfgrow run",
                         holder.empty() ? "" : cat({" (pid ", holder, ")"}),
                         " is writing it; wait for it to finish or choose another folder"}));
    }
    const std::string me = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, me.data(), me.size(), 0);
}

FolderLock::~FolderLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

}  // namespace surfgrow::io
