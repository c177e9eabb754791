// A home point's neighbourhood (internal): the ball around it, grown while the plane test asks for
// more support, judged by the paper's eq. (2) or the disk test, and its registration tolerance.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/detail/grow_context.hpp"

namespace surfgrow::detail {

/// The registration tolerance of an accepted neighbourhood: the user's, per mu of radius; or a few
/// sigmas of the noise measured at its range (its own thickness while the noise is measured),
/// never less than the coordinates' rounding needs, never more than the radius.
double tolerance_of(const GrowContext& ctx, const Neighbourhood& nb);

/// Fits the neighbourhood of sorted point `home` in cube `cube`, whose 27 cubes are `runs27`.
/// kPaper: eq. (2) at mu, or at the adaptive radius if mu holds fewer than min_pts points. kDisk:
/// the radius doubles while the neighbourhood fails the relative tests (too few points, eq. (2),
/// spread, grazing), and the search stops at once where the neighbourhood is thicker than
/// `thickness_sigmas` noise sigmas at its range (an edge, a step, a corner: growing cannot help).
/// Without a known noise profile that limit is not applied (the profile's own sampling). In a fused
/// cloud a ball thicker than growing allows is judged first within its scans' layers (each scan's
/// points about their own mean), and takes the layers' plane where that passes.
Neighbourhood fit_neighbourhood(const GrowContext& ctx, std::uint32_t home, const Vec3f& h,
                                std::uint32_t cube, std::span<const Range> runs27,
                                std::vector<Range>& wide_runs);

}  // namespace surfgrow::detail
