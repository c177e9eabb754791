// A sample of values reduced to the figures the evaluation reports: count, mean, median, p95, max.
#pragma once

#include <cstdint>
#include <vector>

namespace surfgrow::eval {

/// Summary of a sample. Every figure is NaN when the sample is empty.
struct Distribution {
    std::uint64_t count = 0;
    double mean = 0.0;
    double median = 0.0;
    double p95 = 0.0;  ///< 95th percentile, nearest rank: the ceil(0.95 n)-th smallest value
    double max = 0.0;
};

/// Summarises `values` (reordered in place). The median of an even count is the mean of the two
/// middle values. The result depends only on the multiset of values, never on their order.
[[nodiscard]] Distribution summarize(std::vector<double>& values);

/// Nearest-rank q-quantile (0 < q <= 1) of `values` (reordered in place); NaN when empty.
[[nodiscard]] double quantile(std::vector<double>& values, double q);

}  // namespace surfgrow::eval
