// The evaluation's headline figures by name: what --require checks and eval.json's "metrics".
#pragma once

#include <string_view>
#include <vector>

#include "surfgrow/eval/evaluation.hpp"

namespace surfgrow::eval {

/// One named figure of an EvalReport.
struct Metric {
    std::string_view name;  ///< e.g. "registered", "normal_median"
    double value = 0.0;     ///< NaN when it could not be computed
    std::string_view unit;  ///< "fraction", "deg", "mm", "count", "ratio"
    std::string_view what;  ///< one line for people
};

/// Every headline figure, in a fixed order (docs/evaluation.md lists them).
[[nodiscard]] std::vector<Metric> metrics(const EvalReport& report);

/// The names metrics() returns, in its order.
[[nodiscard]] std::vector<std::string_view> metric_names();

}  // namespace surfgrow::eval
