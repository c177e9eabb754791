// The statistics of a grown result (internal, stage 4 of growing): each surface's members, the
// registered share by range band, the normals turned towards their sensor, and the surfaces that
// best-fit registration left empty.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/detail/grow_context.hpp"

namespace surfgrow::detail {

/// Marks the input points that are not in the index (invalid, cropped) in result labels.
constexpr std::int32_t kNotIndexed = -2;

/// Stage 4a: each surface's members (count, bounds, mean residual, largest distance), in the
/// index's float frame. Each thread owns a range of surface ids and visits their members in point
/// order, so every residual sum is added up in the same order whatever the thread count. Returns
/// the points registered.
std::uint64_t member_statistics(const CubeIndex& index, std::span<const std::int32_t> labels,
                                std::span<const double> tolerance, int threads,
                                std::vector<Surface>& surfaces);

/// Stage 4b: registration by range band, over the input in its order (integer counts: any split
/// of the work gives the same totals); the not-indexed mark becomes the unregistered label.
std::vector<RangeBand> range_bands(const CloudView& cloud, const Orientation& orient,
                                   double band_width, int threads,
                                   std::span<std::int32_t> input_labels);

/// Stage 4c: every normal faces its home point's sensor (or +z when none is known). A guessed
/// frame origin that sees a surface edge-on (its plane passes near the origin: a map-frame
/// cloud's floor) says nothing about its side: that surface faces +z instead.
/// Returns the members of those surfaces.
std::uint64_t orient_normals(const CloudView& cloud, const Orientation& orient,
                             std::span<const std::uint32_t> original,
                             std::span<const std::uint32_t> home_of, double max_incidence_deg,
                             int threads, std::vector<Surface>& surfaces);

/// Stage 4d: best-fit registration can take every member of a surface; such surfaces are dropped
/// (ids stay in home order) and the labels renumbered. Returns how many were dropped.
std::uint64_t drop_empty_surfaces(int threads, std::vector<Surface>& surfaces,
                                  std::span<std::int32_t> input_labels);

}  // namespace surfgrow::detail
