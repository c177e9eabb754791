// calibration.json: how the laser sits on the tilt servo, as `surfgrow calibrate` estimated it
// and `scan2cloud` applies it (docs/formats.md, "calibration.json").
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/scanner/calibration.hpp"

namespace surfgrow::io {

/// The file's text: the estimate with its uncertainty, the surface and the scans it came from.
[[nodiscard]] std::string calibration_to_json(const scanner::CalibrationResult& result,
                                              const std::vector<std::string>& scans);

/// Writes calibration_to_json atomically.
void write_calibration_file(const std::filesystem::path& path,
                            const scanner::CalibrationResult& result,
                            const std::vector<std::string>& scans);

/// The mounting a calibration file holds. `name` prefixes messages. Not JSON, another format, or
/// a value missing or out of range (offset under 1 m in size, zero within 10 deg, both finite)
/// throw Error(kMalformedInput).
[[nodiscard]] scanner::Calibration parse_calibration_json(std::string_view text,
                                                          std::string_view name);

/// Reads a calibration file: Error(kCannotOpen) if it cannot be read, else as
/// parse_calibration_json.
[[nodiscard]] scanner::Calibration read_calibration_file(const std::filesystem::path& path);

}  // namespace surfgrow::io
