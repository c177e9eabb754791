// The evaluation through the bound planes: each point judged by its face's plane, not its patch.
#pragma once

#include <span>
#include <vector>

#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/face_detection.hpp"
#include "surfgrow/planes/bound_planes.hpp"

namespace surfgrow::eval {

/// The surfaces of `result` with each normal replaced by its bound plane's (planes.json): what a
/// robot that works along the planes is given. Surfaces in no plane keep their own.
[[nodiscard]] std::vector<Surface> surfaces_through_planes(std::span<const Surface> surfaces,
                                                           const BoundPlanes& planes);

/// Fills report.planes: the normal figures through the bound planes, and the faces detected.
/// `grown` is what `report` evaluated.
void add_plane_figures(EvalReport& report, const CloudView& cloud, const GrowOutcome& grown,
                       const BoundPlanes& planes, std::span<const scanner::Face> faces);

}  // namespace surfgrow::eval
