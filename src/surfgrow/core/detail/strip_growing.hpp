// Strips (internal, stage 3b of growing): faces narrower than any ball around them, grown from the
// points that neither growing nor the leftover pass gave to a surface.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/detail/grow_context.hpp"

namespace surfgrow::detail {

/// Stage 3b (kDisk, noise measured): a flange's 20 mm edge or a plate's end never passes the disk
/// test, since every ball that holds enough of it also holds the faces on either side, and its
/// points fit neither face's plane. Once those faces hold their points, what is left of the strip
/// is a plane of its own: each unregistered point in index order is a home whose neighbourhood of
/// unregistered points only, at mu and growing by sqrt(2) up to the adaptive radius, is judged by
/// the strip test (judge_strip); a strip takes the unregistered points within its tolerance of its
/// plane. A home that grows no strip leaves the leftovers within mu of it untried as homes.
/// Appends the strips to `surfaces`, `home_of` and `tolerance` and labels their points in
/// `ctx.labels`; returns how many it grew. Homes in index order within each of the grower's
/// `slabs`, the even slabs in parallel and then the odd ones (a ball never reaches past the next
/// slab); strips numbered in slab order, even slabs first: the same result for any thread count.
/// The grower calls it for clouds of one scan only (see surface_grower.cpp).
std::uint64_t grow_strips(const GrowContext& ctx, std::span<const Slab> slabs, int threads,
                          std::vector<Surface>& surfaces, std::vector<std::uint32_t>& home_of,
                          std::vector<double>& tolerance);

/// Stage 3b, last (after the leftover pass over the strips): a strip's plane holds along its face
/// beyond the leftover pass's reach. A flange's edge far from the sensor is two or three scan
/// lines, which no ball there reads as a plane, yet the strip grown nearer lies in its plane.
/// Round by round, each leftover within reach of a point a strip took in the round before (in
/// the first, of any of its members) and within the strip's tolerance of its plane joins the
/// strip it fits best (ties by number); rounds end when one takes none. The reach is
/// kMissRadiusPerMu mu, or the strip's radius where larger (its ball grew to hold enough points:
/// beyond the sensor's spacing there). Each round judges against each strip's plane refitted to
/// all its members so far (along a long strip its first ball's normal leans by degrees); a strip
/// that reached farther keeps that plane, and its members beyond its tolerance of it are left
/// out. Strips are surfaces `first_strip` on. Serial and in point order: the same for any thread
/// count. Returns the strips' members gained (less those left out).
std::int64_t extend_strips(const GrowContext& ctx, std::int32_t first_strip,
                           std::vector<Surface>& surfaces, std::span<const double> tolerance);

/// Stage 3b's last step (the disk test with the leftover pass, fused clouds too): every surface
/// reaches along its face as strips do, by the same rounds, from the points registered since
/// growing (`frontier`, sorted): a far face seen at grazing incidence (the stairs' side wall at
/// 3.5-4 m, 76 degrees) is points 50-100 mm apart, out of one leftover pass's reach of the
/// surfaces grown nearer, yet in their plane. A surface keeps its plane (its normal was pooled);
/// each point joins the surface it fits best. Serial and in point order: the same for any thread
/// count. Returns the points registered.
std::int64_t extend_surfaces(const GrowContext& ctx, std::vector<Surface>& surfaces,
                             std::span<const double> tolerance,
                             std::vector<std::uint32_t> frontier);

}  // namespace surfgrow::detail
