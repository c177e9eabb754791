// Bounds on evaluation metrics, as given to `surfgrow eval --require` (docs/evaluation.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/eval/evaluation.hpp"

namespace surfgrow::eval {

enum class Comparison { kAtLeast, kAtMost, kAbove, kBelow };  // >=  <=  >  <

/// One bound: metric OP value.
struct Requirement {
    std::string metric;
    Comparison op = Comparison::kAtLeast;
    double bound = 0.0;
    std::string text;  ///< as written, e.g. "registered>=0.99"
};

/// Parses comma-separated bounds "name>=value,name<=value" (also > and <; blanks allowed; a value
/// ending in % is divided by 100, so "registered>=99%" is "registered>=0.99"). Names are those of
/// metric_names(). Throws Error(kUsage) naming the bad part and listing the metrics.
[[nodiscard]] std::vector<Requirement> parse_requirements(std::string_view text);

struct RequirementCheck {
    Requirement requirement;
    double value = 0.0;  ///< the metric's value (NaN: not available, which fails the bound)
    bool met = false;
};

/// Checks every requirement against `report`, in order.
[[nodiscard]] std::vector<RequirementCheck> check_requirements(
    const std::vector<Requirement>& requirements, const EvalReport& report);

/// "<=", ">=", "<", ">".
[[nodiscard]] std::string_view to_string(Comparison op);

}  // namespace surfgrow::eval
