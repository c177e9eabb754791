// The paper's range filter, eq. (1): a trimmed mean of the n readings taken along one ray.
#pragma once

#include <cstdint>
#include <span>

namespace surfgrow::scanner {

/// Eq. (1): sort the n readings d_0 <= ... <= d_{n-1}, drop q from each end and average the
/// remaining n - 2q. (The paper writes the sum over j = q..n-q, which would be n - 2q + 1 terms;
/// its text says "averaging the remaining n-2q values", which is what this does: d_q..d_{n-q-1}.)
///
/// Readings that are 0 (no return) or outside [min_range_mm, max_range_mm] (the URG's error codes
/// 1..19 lie below 20 mm) are not readings: they are removed before sorting.
///
/// Fewer valid readings (v < n): q are still trimmed from each end of the v valid ones and the
/// v - 2q in the middle are averaged, so dropouts never weaken the protection against outliers
/// (mixed pixels flicker, so a ray that lost readings is the one most likely to hold one). When
/// v <= 2q nothing is left and the ray gives no range. So with fewer than n - 2q valid readings the
/// estimate averages fewer values, down to a single median-like value, and then none.
class RangeFilter {
  public:
    /// Throws Error(kInvalidParameter) unless q >= 0, n > 2q (n = readings_per_ray) and
    /// 1 <= min_range_mm < max_range_mm.
    RangeFilter(int readings_per_ray, int trim_q, std::uint16_t min_range_mm,
                std::uint16_t max_range_mm);

    [[nodiscard]] int readings_per_ray() const { return n_; }
    [[nodiscard]] int trim_q() const { return q_; }

    /// The filtered range in millimetres, or NaN when the ray gives no range. `readings_mm` holds
    /// one ray's readings (normally n of them; any count up to 255 is accepted).
    [[nodiscard]] double operator()(std::span<const std::uint16_t> readings_mm) const;

  private:
    int n_;
    int q_;
    std::uint16_t min_mm_;
    std::uint16_t max_mm_;
};

}  // namespace surfgrow::scanner
