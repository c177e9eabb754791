// Helpers shared by the scanner's file formats (raw scans, scenes, poses): whole-file reads with
// a size cap, and Error messages that name the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "surfgrow/core/error.hpp"

namespace surfgrow::io::detail {

/// The bytes of `path`. Throws Error(kCannotOpen) if it is missing, a folder or unreadable, and
/// Error(kMalformedInput) if it is larger than `max_bytes` (before reading any of it).
std::string read_file_capped(const std::filesystem::path& path, std::size_t max_bytes,
                             std::string_view what);

/// Rethrows `e` with "name: " in front of its message, keeping its code.
[[noreturn]] void rethrow_in(std::string_view name, const Error& e);

/// Throws Error(kMalformedInput, "name: message").
[[noreturn]] void malformed(std::string_view name, std::string_view message);

/// Throws Error(kMalformedInput) if JSON `text` nests arrays/objects deeper than `max_depth`
/// (a hostile file must not exhaust the stack of a recursive parser or destructor), and
/// Error(kCloudTooLarge) if parsing it would need more memory than memory_budget() allows.
void check_json_limits(std::string_view text, std::string_view name, int max_depth = 64);

}  // namespace surfgrow::io::detail
