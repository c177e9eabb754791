// The evaluation through the bound planes: each point judged by its face's plane, not its patch.
#pragma once

#include <span>
#include <vector>

#include "surfgrow/core/bound_planes.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/face_detection.hpp"

namespace surfgrow::eval {

/// The surfaces of `result` with each normal replaced by its bound plane's (planes.json): what a
/// robot that works along the planes is given. Surfaces in no plane keep their own.
[[nodiscard]] std::vector<Surface> surfaces_through_planes(std::span<const Surface> surfaces,
                                                           const BoundPlanes& planes);

/// evaluate() with every registered point's normal taken from its bound plane.
[[nodiscard]] EvalReport evaluate_through_planes(const PointCloud& cloud, const GrowResult& result,
                                                 const BoundPlanes& planes,
                                                 std::span<const scanner::Face> faces,
                                                 const EvalOptions& options = {});

/// Fills report.planes: the normal figures through the bound planes, and the faces detected.
/// `grown` is what `report` evaluated.
void add_plane_figures(EvalReport& report, const PointCloud& cloud, const GrowOutcome& grown,
                       const BoundPlanes& planes, std::span<const scanner::Face> faces);

/// SegComp correct detection (T = 0.8) of the scene's planar faces with >= 500 points by the
/// bound planes.
[[nodiscard]] FaceDetection plane_detections(const PointCloud& cloud, const GrowResult& result,
                                             const BoundPlanes& planes,
                                             std::span<const scanner::Face> faces);

}  // namespace surfgrow::eval
