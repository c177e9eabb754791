// The edge pass (internal, stage 3c of growing, fused clouds only): a registered point beside a
// surface across an edge goes to the surface whose plane, shifted to its own scan's layer, it fits
// best.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/detail/grow_context.hpp"

namespace surfgrow::detail {

/// Fused clouds. Within a few noise sigmas of an edge a point lies within the tolerance of both
/// faces' planes, and each scan sees each face a little off the others (its layer: range bias,
/// pose error), so best fit against the planes alone splits that strip between the faces about
/// evenly. Here each surface's plane is shifted, per scan, to the mean of that scan's members,
/// and each registered point in a cube whose 27 cubes hold surfaces more than 30 degrees apart
/// moves to the surface whose shifted plane it fits best among those with a member within mu
/// and within their tolerance, if that surface lies across the edge from its own (a coplanar one
/// would not change its normal). The moves are decided on the labels as the leftover pass left
/// them and applied after: the same result for any slab order and thread count. Skipped when the
/// per-scan table would outgrow the labels (surfaces x scans > 4 x points). Returns the moves.
std::uint64_t reassign_at_edges(const GrowContext& ctx, std::span<const Slab> slabs,
                                const std::vector<Surface>& surfaces,
                                std::span<const double> tolerance, int threads,
                                std::span<std::int32_t> labels);

}  // namespace surfgrow::detail
