// A whole input file in memory, read with one read() so parsers work on a flat buffer.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string_view>

namespace surfgrow::io {

/// The bytes of a file. Regular files are read with a single read() into a buffer of their size
/// (no zero-filling); pipes and devices are read in growing chunks.
class FileBytes {
  public:
    /// Reads `path`. Throws Error(kCannotOpen) when it is missing, a folder or unreadable.
    [[nodiscard]] static FileBytes read(const std::filesystem::path& path);

    [[nodiscard]] std::string_view view() const { return {data_.get(), size_}; }
    [[nodiscard]] std::size_t size() const { return size_; }
    [[nodiscard]] bool empty() const { return size_ == 0; }

  private:
    std::unique_ptr<char[]> data_;
    std::size_t size_ = 0;
};

}  // namespace surfgrow::io
