#include "surfgrow/eval/distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surfgrow::eval {

double quantile(std::vector<double>& values, double q) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    const auto n = values.size();
    auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
    rank = std::clamp<std::size_t>(rank, 1, n);
    auto nth = values.begin() + static_cast<std::ptrdiff_t>(rank - 1);
    std::nth_element(values.begin(), nth, values.end());
    return *nth;
}

Distribution summarize(std::vector<double>& values) {
    Distribution d;
    d.count = values.size();
    if (values.empty()) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        d.mean = d.median = d.p95 = d.max = nan;
        return d;
    }
    // Sorting makes the sum's order, and so its rounding, independent of the input order.
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    double sum = 0.0;
    for (const double v : values) sum += v;
    d.mean = sum / static_cast<double>(n);
    d.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    const auto rank = std::clamp<std::size_t>(
        static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n))), 1, n);
    d.p95 = values[rank - 1];
    d.max = values.back();
    return d;
}

}  // namespace surfgrow::eval
