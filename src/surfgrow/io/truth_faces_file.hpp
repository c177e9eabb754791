// Ground-truth faces of a simulated scene (the true planes, discs and cylinder sides), as JSON,
// for evaluating grown surfaces against the scene (docs/scene-format.md).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::io {

/// {"format": "surfgrow-truth-faces", "version": 1, "scene": name, "faces": [...]}: every face of
/// the scene with its id (the label of the points on it), its primitive and the primitive's name,
/// and its geometry: rectangles (center, normal, d of n.x + d = 0, u_axis, v_axis, size), discs
/// (center, normal, d, radius) and cylinder sides (center, axis, radius, length).
[[nodiscard]] std::string truth_faces_to_json(const scanner::Scene& scene);

/// Writes truth_faces_to_json atomically.
void write_truth_faces(const std::filesystem::path& path, const scanner::Scene& scene);

/// Reads the faces back (ids, kinds and geometry; primitive names are not kept). Errors:
/// kCannotOpen, kMalformedInput (bad JSON, missing keys, ids not 0, 1, 2, ... in order).
[[nodiscard]] std::vector<scanner::Face> parse_truth_faces_json(std::string_view text,
                                                                std::string_view name);
[[nodiscard]] std::vector<scanner::Face> read_truth_faces(const std::filesystem::path& path);

}  // namespace surfgrow::io
