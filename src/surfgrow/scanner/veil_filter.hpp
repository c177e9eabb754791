// Mixed pixels in the depth gap between two surfaces (the "veil" behind an object's silhouette):
// a beam that straddles a depth edge returns a blend of the two ranges, a point that belongs to
// neither surface. Across a silhouette they form a thin sheet along the rays, locally a plane,
// which no neighbourhood test can tell from a surface seen at a slant; in the scan's own order
// of rays they stand out.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/scanner/tilting_scanner.hpp"

namespace surfgrow::scanner {

/// When a ray is a mixed pixel: both its neighbours along the scan line (the steps before and
/// after), or both across the tilt rows, lie within `angle_deg` of its own line of sight, one
/// nearer and one farther, each more than `min_step_mm` away in range. The point then floats in
/// the depth gap between them. The step floor keeps range noise out: at the tilt axis's pole,
/// where neighbouring tilt rows aim at nearly the same spot, neighbours always lie along the
/// ray, a few noise sigmas apart.
///
/// Off by default (angle 0); 10 degrees is the angle studied (docs/algorithm.md, "Mixed pixels
/// dropped where the scan was taken"): on the built-in scenes it drops no point of a face.
struct VeilFilter {
    double angle_deg = 0.0;     ///< 0 turns the filter off; 10 studied
    double min_step_mm = 30.0;  ///< three times the URG-04LX's datasheet accuracy up to 1 m
};

/// The angle the study chose (kept off by default: docs/algorithm.md says why).
inline constexpr double kStudiedVeilAngleDeg = 10.0;

/// Throws Error(kInvalidParameter) for an angle outside [0, 45] degrees or a negative or
/// non-finite step.
void validate(const VeilFilter& filter);

/// For each ray of a scan (tilt-major, as TiltingScanner numbers them) whether it is a mixed
/// pixel by `filter`; `range_mm` holds each ray's filtered range (NaN: none). All false when the
/// filter is off. The same for any thread count.
[[nodiscard]] std::vector<std::uint8_t> veil_rays(const TiltingScanner& scanner,
                                                  std::span<const double> range_mm,
                                                  const VeilFilter& filter);

}  // namespace surfgrow::scanner
