// The evaluation as JSON (eval.json): metrics by name, every figure, range bands, faces.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/requirement.hpp"

namespace surfgrow::eval {

/// {"format": "surfgrow-eval", "version": 1, "metrics": {...}, "registration": {...},
/// "normals": {...}, "surfaces": {...}, "bands": [...], "faces": [...], "requirements": [...]}.
/// Lengths in metres except the *_mm metrics; NaN and infinity are written as null.
/// Deterministic: the same report gives the same text.
[[nodiscard]] nlohmann::json to_json(const EvalReport& report,
                                     const std::vector<RequirementCheck>& checks = {});

}  // namespace surfgrow::eval
