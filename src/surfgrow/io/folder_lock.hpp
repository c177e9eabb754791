// One writer per output folder: two runs into the same folder never interleave.
#pragma once

#include <filesystem>

namespace surfgrow::io {

/// An exclusive advisory lock (flock) on the file `.NAME.lock` beside folder NAME. The lock lives
/// beside the folder, not in it, because a commit replaces the folder itself. The kernel drops it
/// when the process dies, so a killed run never leaves the folder locked.
class FolderLock {
  public:
    /// Takes the lock for `folder` (an absolute path without a trailing separator). Throws
    /// Error(kCannotWrite) naming the folder and the other process when another run holds it,
    /// and when the lock file cannot be created.
    explicit FolderLock(const std::filesystem::path& folder);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

  private:
    int fd_ = -1;
};

}  // namespace surfgrow::io
