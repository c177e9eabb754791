// Scan poses files: one sensor-to-world pose per scan, as text or JSON (docs/scanner.md).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "surfgrow/scanner/pose.hpp"

namespace surfgrow::io {

/// Text: one pose per line, either 16 numbers (the 4x4 matrix, row-major) or 6 numbers
/// x y z roll pitch yaw (metres, degrees; R = Rz(yaw) Ry(pitch) Rx(roll)). Numbers are separated
/// by spaces, tabs or commas; '#' starts a comment; blank lines are skipped. `name` prefixes
/// errors, which give the line: Error(kMalformedInput) for a bad number or count or no pose at
/// all, Error(kInvalidParameter) for a matrix that is not a rigid transform.
[[nodiscard]] std::vector<scanner::Pose> parse_poses_text(std::string_view text,
                                                          std::string_view name);

/// JSON: {"poses": [pose, ...]} or a bare [pose, ...], where a pose is a 16- or 6-number array
/// (as one text line), {"matrix": [[4 numbers] x 4]} (or 16 numbers), or
/// {"position": [x, y, z], "rpy_deg": [roll, pitch, yaw]}. Errors as parse_poses_text.
[[nodiscard]] std::vector<scanner::Pose> parse_poses_json(std::string_view text,
                                                          std::string_view name);

/// Reads a poses file: JSON if its first non-blank character is '{' or '[', text otherwise.
/// Throws Error(kCannotOpen) if it cannot be read.
[[nodiscard]] std::vector<scanner::Pose> read_poses_file(const std::filesystem::path& path);
/// The same for a poses file held in memory; `name` prefixes errors.
[[nodiscard]] std::vector<scanner::Pose> parse_poses_file(std::string_view text,
                                                          std::string_view name);

/// One line of 16 numbers per pose (shortest round-trip form), after a comment header.
[[nodiscard]] std::string poses_to_text(const std::vector<scanner::Pose>& poses);

/// Writes poses_to_text atomically.
void write_poses_file(const std::filesystem::path& path, const std::vector<scanner::Pose>& poses);

/// One pose in any of the JSON forms above; `where` names it in errors (e.g. "file: pose 3").
[[nodiscard]] scanner::Pose pose_from_json(const nlohmann::json& j, std::string_view where);
/// {"matrix": [[...], [...], [...], [...]]}, exact to the last bit.
[[nodiscard]] nlohmann::json pose_to_json(const scanner::Pose& pose);

}  // namespace surfgrow::io
