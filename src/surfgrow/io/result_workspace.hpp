// The workspace parameters of a stored result (viewpoint, crop), which read_result_json() leaves
// out: the occupancy grid needs them to rebuild the grower's index exactly.
#pragma once

#include <filesystem>

#include "surfgrow/core/grower_config.hpp"

namespace surfgrow::io {

/// Sets config.viewpoint and config.crop from surfaces.json's "parameters" (absent ones stay
/// unset). Throws Error(kCannotOpen) / Error(kMalformedInput) naming the file.
void read_workspace_parameters(const std::filesystem::path& surfaces_json, GrowerConfig& config);

}  // namespace surfgrow::io
