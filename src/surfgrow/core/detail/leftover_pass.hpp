// The leftover pass (internal, stage 3 of growing): each point left unregistered goes to the
// neighbouring surface whose plane it fits best, within that surface's tolerance; in a fused
// cloud, also to a surface whose plane its own scan's layer lies beside.
#pragma once

#include <span>
#include <vector>

#include "surfgrow/core/detail/grow_context.hpp"

namespace surfgrow::detail {

/// Stage 3: each point left unregistered goes to the best-fitting neighbouring surface; only to
/// surfaces numbered `first_surface` or above (after strips: the strips alone, since no other
/// surface fits a point the first pass left).
void attach_leftovers(const GrowContext& ctx, std::span<const Slab> slabs,
                      const std::vector<Surface>& surfaces, std::span<const double> tolerance,
                      int threads, std::span<std::int32_t> labels, std::int32_t first_surface = 0);

}  // namespace surfgrow::detail
