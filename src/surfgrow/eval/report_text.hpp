// The evaluation for people: one line (the demo, CI logs) and a short table (`surfgrow eval`).
#pragma once

#include <string>
#include <vector>

#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/requirement.hpp"

namespace surfgrow::eval {

/// "eval: 98.1% registered (planar 99.2%, within 1 m 99.9%), normal error median 0.9 deg p95
/// 4.3 deg, facing sensor 100.0%, purity 99.4%"
[[nodiscard]] std::string eval_line(const EvalReport& report);

/// "range bands (planar registered, normal median): 0.0-0.5 m 100.0% 0.81 deg, ..."; empty when
/// no point has a scan origin.
[[nodiscard]] std::string bands_line(const EvalReport& report);

/// Several lines: registration by kind, normals, surfaces, and one row per range band.
[[nodiscard]] std::string summary_text(const EvalReport& report);

/// One line per requirement: "require registered>=0.99: 0.9912 ok" / "... FAILED".
[[nodiscard]] std::string requirements_text(const std::vector<RequirementCheck>& checks);

}  // namespace surfgrow::eval
