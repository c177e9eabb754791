#include "surfgrow/scanner/range_filter.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

RangeFilter::RangeFilter(int readings_per_ray, int trim_q, std::uint16_t min_range_mm,
                         std::uint16_t max_range_mm)
    : n_(readings_per_ray), q_(trim_q), min_mm_(min_range_mm), max_mm_(max_range_mm) {
    if (q_ < 0)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"trim q must be >= 0, got ", std::to_string(q_)}));
    if (std::int64_t{n_} <= 2 * std::int64_t{q_})  // --trim 2^30 once overflowed here
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"eq. (1) needs n > 2q readings per ray, got n = ", std::to_string(n_),
                         " and q = ", std::to_string(q_)}));
    if (min_mm_ < 1 || max_mm_ <= min_mm_)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"range limits must satisfy 1 <= min < max mm, got ",
                         std::to_string(min_mm_), "..", std::to_string(max_mm_)}));
}

double RangeFilter::operator()(std::span<const std::uint16_t> readings_mm) const {
    std::array<std::uint16_t, 256> valid{};
    std::size_t v = 0;
    for (const std::uint16_t r : readings_mm) {
        if (v == valid.size()) break;
        if (r >= min_mm_ && r <= max_mm_) valid[v++] = r;
    }
    const std::size_t q = static_cast<std::size_t>(q_);
    if (v <= 2 * q) return std::numeric_limits<double>::quiet_NaN();
    std::sort(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(v));
    std::uint64_t sum = 0;
    for (std::size_t i = q; i < v - q; ++i) sum += valid[i];
    return static_cast<double>(sum) / static_cast<double>(v - 2 * q);
}

}  // namespace surfgrow::scanner
