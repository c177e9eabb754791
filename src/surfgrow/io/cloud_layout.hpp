// What the writers put in a file for a given cloud: float or double coordinates, normals and
// labels or not.
#pragma once

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

struct CloudLayout {
    bool doubles = false;  ///< coordinates as double with the offset added back (offset != 0)
    bool normals = false;  ///< a float normal per point (after x y z, before the label)
    bool labels = false;   ///< a label per point
};

/// Doubles whenever the cloud has an offset (its points are only meaningful with it); normals
/// and labels when asked for and present. Labels of the wrong length are a bug in the caller;
/// normals of the wrong length (set by a user, e.g. from Python) are refused with
/// Error(kInvalidParameter), whether or not they are asked for, before anything is written.
[[nodiscard]] inline CloudLayout layout_for(const CloudView& cloud, bool want_labels,
                                            bool want_normals) {
    if (!cloud.labels.empty() && cloud.labels.size() != cloud.points.size()) {
        throw Error(ErrorCode::kInternal,
                    cat({"cloud has ", std::to_string(cloud.labels.size()), " labels for ",
                         std::to_string(cloud.points.size()), " points"}));
    }
    if (!cloud.normals.empty() && cloud.normals.size() != cloud.points.size()) {
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"the cloud has ", std::to_string(cloud.normals.size()), " normals for ",
                         std::to_string(cloud.points.size()),
                         " points; give one normal per point, or none"}));
    }
    return {cloud.offset != Vec3d::Zero(), want_normals && cloud.has_normals(),
            want_labels && cloud.has_labels()};
}

/// Point i in file coordinates (offset added back).
[[nodiscard]] inline Vec3d absolute_point(const CloudView& cloud, std::size_t i) {
    return cloud.points[i].cast<double>() + cloud.offset;
}

}  // namespace surfgrow::io
