// The raw-scan file (.sgraw): n readings per ray per tilt, the scanner spec and the pose
// (docs/raw-scan-format.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "surfgrow/scanner/raw_scan.hpp"

namespace surfgrow::io {

/// Version 1: readings and ground truth. Version 2 adds what an acquisition records (read-back
/// tilt angles, sensor time stamps, a partial scan's plan, its note and stop reason); a scan
/// without them is written as version 1, so older readers keep reading simulated scans.
inline constexpr std::uint32_t kRawScanVersion = 2;
/// Bytes before the readings: magic, version, flags, spec, pose, reading count.
inline constexpr std::size_t kRawScanHeaderBytes = 240;

/// The file's bytes. Throws Error(kInvalidParameter) if the scan is inconsistent
/// (RawScan::validate).
[[nodiscard]] std::string encode_raw_scan(const scanner::RawScan& scan);

/// Parses a raw scan; `name` (the file) prefixes error messages. Structural defects (bad magic,
/// unknown version or flags, a size that does not match the header, a checksum mismatch, a ground
/// truth id below -1) throw Error(kMalformedInput); a well-formed file describing an invalid
/// scanner or a non-rigid pose throws Error(kInvalidParameter). Sizes are checked against the
/// header before anything is allocated.
[[nodiscard]] scanner::RawScan decode_raw_scan(std::string_view bytes, std::string_view name);

/// Writes atomically (write_atomically): the file appears whole or not at all.
void write_raw_scan(const std::filesystem::path& path, const scanner::RawScan& scan);

/// Reads a raw scan. Throws Error(kCannotOpen) if the file cannot be read, otherwise as
/// decode_raw_scan.
[[nodiscard]] scanner::RawScan read_raw_scan(const std::filesystem::path& path);

}  // namespace surfgrow::io
