// Scene files: the primitives of a structure to scan, as JSON (docs/scene-format.md).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::io {

inline constexpr int kSceneFormatVersion = 1;

/// Parses a scene: {"format": "surfgrow-scene", "version": 1, "name": ..., "primitives": [...],
/// "scanner": {...}}. `name` (the file) prefixes errors. Invalid JSON, a missing or unknown key,
/// a wrong type or array length throw Error(kMalformedInput) naming the primitive; values out of
/// range (a negative size, axes not perpendicular, a non-rigid scanner pose) throw
/// Error(kInvalidParameter). The returned description is valid for scanner::Scene.
[[nodiscard]] scanner::SceneDescription parse_scene_json(std::string_view text,
                                                         std::string_view name);

/// Reads a scene file. Throws Error(kCannotOpen) if it cannot be read, otherwise as
/// parse_scene_json.
[[nodiscard]] scanner::SceneDescription read_scene_file(const std::filesystem::path& path);

/// The scene as JSON that parse_scene_json reads back exactly (numbers in round-trip form;
/// rotations as matrices). Throws Error(kInvalidParameter) if the description is invalid.
[[nodiscard]] std::string scene_to_json(const scanner::SceneDescription& scene);

/// Writes scene_to_json atomically.
void write_scene_file(const std::filesystem::path& path, const scanner::SceneDescription& scene);

}  // namespace surfgrow::io
