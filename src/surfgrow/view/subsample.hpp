// Choosing which points of a large cloud go into the viewer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"

namespace surfgrow::view {

/// The indices of the finite points of `cloud`, in increasing order; if there are more than
/// `max_points`, `max_points` of them chosen by a fixed hash of the index (the same points every
/// time, whatever the machine, and spread evenly over the cloud without the stripes that taking
/// every k-th point of a scan-ordered cloud leaves).
[[nodiscard]] std::vector<std::uint32_t> choose_points(const CloudView& cloud,
                                                       std::size_t max_points);

}  // namespace surfgrow::view
