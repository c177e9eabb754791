// Outputs that appear whole or not at all: write to a temporary, rename into place.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace surfgrow::io {

/// Writes `path` through `writer` into a temporary file beside it, then renames it over `path`.
/// On any failure (the writer throws, the disk fills) the temporary is removed, `path` keeps its
/// old content, and Error(kCannotWrite) names the file (the writer's own Error passes through).
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& writer);

/// A set of output files in one folder that are published together.
///
/// Each file is staged under a temporary name in the target folder (same file system, so the
/// final rename is atomic) and renamed into place by commit(). If the transaction is destroyed
/// before commit() -- an exception, a bad input found late -- every staged file is removed and
/// the folder's previous outputs are untouched.
class OutputTransaction {
  public:
    /// Creates `dir` if needed. Throws Error(kCannotWrite) if it cannot.
    explicit OutputTransaction(std::filesystem::path dir);
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;

    [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }

    /// Stages `name` (a file name inside dir()) by running `writer` on a binary stream.
    void add(const std::string& name, const std::function<void(std::ostream&)>& writer);

    /// Final paths of the files staged so far.
    [[nodiscard]] std::vector<std::filesystem::path> files() const;

    /// Renames every staged file into place. Throws Error(kCannotWrite) on failure.
    void commit();

  private:
    struct Staged {
        std::filesystem::path temp;
        std::filesystem::path final_path;
    };
    std::filesystem::path dir_;
    std::vector<Staged> staged_;
    bool committed_ = false;
};

}  // namespace surfgrow::io
