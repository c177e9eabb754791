// What the writers put in a file for a given cloud: float or double coordinates, labels or not.
#pragma once

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

struct CloudLayout {
    bool doubles = false;  ///< coordinates as double with the offset added back (offset != 0)
    bool labels = false;   ///< a label per point
};

/// Doubles whenever the cloud has an offset (its points are only meaningful with it); labels
/// when asked for and present. Labels of the wrong length are a bug in the caller.
[[nodiscard]] inline CloudLayout layout_for(const PointCloud& cloud, bool want_labels) {
    if (!cloud.labels.empty() && cloud.labels.size() != cloud.points.size()) {
        throw Error(ErrorCode::kInternal,
                    cat({"cloud has ", std::to_string(cloud.labels.size()), " labels for ",
                         std::to_string(cloud.points.size()), " points"}));
    }
    return {cloud.offset != Vec3d::Zero(), want_labels && cloud.has_labels()};
}

/// Point i in file coordinates (offset added back).
[[nodiscard]] inline Vec3d absolute_point(const PointCloud& cloud, std::size_t i) {
    return cloud.points[i].cast<double>() + cloud.offset;
}

}  // namespace surfgrow::io
