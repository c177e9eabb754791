// Which points of a cloud the grower indexes: finite and inside the robot's workspace crop.
// The one place this rule (crop centre included) is written; occupancy and free space use it too.
#pragma once

#include <cstdint>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/grower_config.hpp"

namespace surfgrow {

/// The centre of the radius crop: the crop's own, else the viewpoint (the config's, then the
/// cloud's), else the origin of the cloud's file frame.
[[nodiscard]] Vec3d crop_centre(const CloudView& cloud, const GrowerConfig& config);

/// The points inside the workspace crop.
struct WorkspaceMask {
    /// 1 for a finite point inside the crop, 0 otherwise; empty when no crop is set (every
    /// finite point is in).
    std::vector<std::uint8_t> inside;
    std::uint64_t cropped = 0;  ///< finite points outside the crop
};

/// The workspace mask of `cloud` for `config.crop`.
[[nodiscard]] WorkspaceMask workspace_mask(const CloudView& cloud, const GrowerConfig& config);

/// The points the grower indexes for `config`: finite and inside the workspace crop (1), others
/// (0); one entry per point, crop or not.
[[nodiscard]] std::vector<std::uint8_t> grown_point_mask(const CloudView& cloud,
                                                         const GrowerConfig& config);

}  // namespace surfgrow
