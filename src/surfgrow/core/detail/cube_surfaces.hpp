// Per cube of the index, the distinct surfaces its points were registered to (internal): what the
// passes after growing read instead of every point around a point.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cube_index.hpp"

namespace surfgrow::detail {

/// Per cube, the distinct surfaces its points were grown into (sorted). A leftover's search reads
/// the surfaces around it from these lists rather than every point around it (a dense scan holds
/// thousands of points within mu of a leftover, on a handful of surfaces), and scans points only
/// to confirm that a surface it would take has a member within reach.
struct CubeSurfaces {
    std::vector<std::uint32_t> start;  // cube_count() + 1 entries
    std::vector<std::int32_t> ids;

    [[nodiscard]] std::span<const std::int32_t> of(std::size_t c) const {
        return {ids.data() + start[c], ids.data() + start[c + 1]};
    }
    [[nodiscard]] bool holds(std::size_t c, std::int32_t sid) const {
        const auto list = of(c);
        return std::binary_search(list.begin(), list.end(), sid);
    }
};

/// The lists of every cube, for the labels (sorted index order) of surfaces `first_surface` and up.
CubeSurfaces cube_surfaces(const CubeIndex& index, std::span<const std::int32_t> labels,
                           std::int32_t first_surface, int threads);

}  // namespace surfgrow::detail
