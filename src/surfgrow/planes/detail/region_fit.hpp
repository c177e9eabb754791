// A region's plane from its points' pooled moments, and when those points cannot define it
// (docs/planes-and-coverage.md, "Per region").
#pragma once

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/moments.hpp"
#include "surfgrow/core/surface.hpp"

namespace surfgrow::detail {

struct Fit {
    Vec3d normal = Vec3d::UnitZ();
    Vec3d eigenvalues = Vec3d::Zero();  ///< ascending
    bool degenerate = true;             ///< the points define no plane: keep `normal` out of it
};

/// Least-squares plane of the moments; degenerate when the points are (nearly) collinear.
[[nodiscard]] Fit fit_moments(const CentredMoments& m);

/// Adds a normal (or a sum of them) to a sum, sign-aligned with it, times `weight`.
void add_normal(Vec3d& sum, const Vec3d& normal, double weight);

/// Adds a patch's normal to a region's judging sum (region_fit), weighted by `weight`, when the
/// patch's points span its ball in both directions (the default disk test's spread): its normal
/// is then measured, not the arbitrary one of a line or a blob (eq. (2) passes those).
void add_judge(Vec3d& judge, const Surface& patch, double weight);

/// fit_moments, also degenerate where the points spread less across the region than along its
/// normal (a 12 mm plate's end seen head-on by scans whose range noise and pose errors spread it
/// deeper than wide). Their plane then turns 60-90 degrees from its patches', each of which spans
/// its own ball: a plane closer to perpendicular than to parallel to `judge` (add_judge) is that
/// case. Smaller disagreements are the patches' noise (and with eq. (2) their edges): there, and
/// where no patch spans its ball (`judge` zero), the points' plane stands.
[[nodiscard]] Fit region_fit(const CentredMoments& m, const Vec3d& judge);

}  // namespace surfgrow::detail
