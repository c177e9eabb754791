// Outputs that appear whole or not at all, and stay once the command has exited: staged, synced
// to disk, then published by one atomic step (docs/formats.md, "Result folders").
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/io/folder_lock.hpp"

namespace surfgrow::io {

/// Writes `path` through `writer` into a temporary file beside it, syncs it, renames it over
/// `path` and syncs the folder. On any failure (the writer throws, the disk fills) the temporary
/// is removed, `path` keeps its old content, and Error(kCannotWrite) names the file (the writer's
/// own Error passes through). Temporaries of `path` left by killed processes are removed.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& writer);

/// Names the files of an earlier run that a new run replaces even when it does not write them
/// again (so `grow --no-planes` leaves no stale planes.json). Files it does not name are the
/// user's own and are kept.
using PreviousOutputs = std::function<bool(std::string_view file_name)>;

/// A set of output files in one folder, published together: the folder is either exactly its
/// old content or exactly the new one, even if the process is killed or the power fails.
///
/// The files are staged in a sibling folder `.NAME.staging-PID` and synced; commit() carries the
/// files it keeps over from the old folder (hard links), syncs, and swaps the two folders with
/// one renameat2(RENAME_EXCHANGE). Destroyed before commit() -- an exception, a bad input found
/// late -- the staging is removed and the folder is untouched. A lock beside the folder
/// (FolderLock) refuses a second run into it; staging left by a killed run is removed first.
class OutputTransaction {
  public:
    /// Opens a transaction on `dir` (created at commit if it does not exist). Without
    /// `previous`, the folder's present files are kept except those staged or dropped (a
    /// subcommand amending a result); with it, the files it names go as well (a new result).
    /// Throws Error(kCannotWrite) when `dir` is not a folder, is locked, or cannot be staged.
    explicit OutputTransaction(std::filesystem::path dir, PreviousOutputs previous = {});
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;

    /// The folder as given.
    [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }

    /// Stages `name` (a file name inside dir()) by running `writer` on a binary stream.
    void add(const std::string& name, const std::function<void(std::ostream&)>& writer);

    /// Removes `name` from the folder at commit: a file the staged ones make stale.
    void drop(const std::string& name);

    /// Final paths of the files staged so far.
    [[nodiscard]] std::vector<std::filesystem::path> files() const;

    /// Files present in the old folder that commit() removed (dropped or previous outputs).
    [[nodiscard]] const std::vector<std::string>& removed() const { return removed_; }

    /// Publishes the staged files. Throws Error(kCannotWrite) on failure (the folder is then
    /// still the old one).
    void commit();

  private:
    [[nodiscard]] bool keeps(const std::string& name) const;
    void carry_over();

    std::filesystem::path dir_;      ///< as given, for messages
    std::filesystem::path target_;   ///< absolute, symlinks resolved: the folder swapped
    std::filesystem::path staging_;  ///< sibling folder the new content is built in
    PreviousOutputs previous_;
    std::unique_ptr<FolderLock> lock_;
    std::vector<std::string> staged_;
    std::vector<std::string> dropped_;
    std::vector<std::string> removed_;
    bool committed_ = false;
};

}  // namespace surfgrow::io
