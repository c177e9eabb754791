// SegComp's "correct detection" of true faces by found segments (Hoover et al., 1996).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace surfgrow::eval {

struct FaceDetection {
    std::uint64_t faces = 0;           ///< true faces scored (enough points, and asked for)
    std::uint64_t correct = 0;         ///< of those, correctly detected
    std::vector<std::int32_t> missed;  ///< the scored faces not correctly detected
    /// correct / faces; NaN when no face is scored.
    [[nodiscard]] double fraction() const;
};

/// A true face F (truth id per point, -1 none) is correctly detected at tolerance T when the
/// found segments (segment id per point, -1 none) that hold at least T of their own points on F
/// -- coplanar pieces of one face, taken together -- hold at least T of F's points. Unregistered
/// points of F count against it, points of a segment with no truth face against the segment.
/// Faces with fewer than `min_points` points, or whose `scored[id]` is 0 (when `scored` is not
/// empty), are left out. Throws Error(kInvalidParameter) if the sizes differ or T is outside
/// (0.5, 1].
[[nodiscard]] FaceDetection correct_detections(std::span<const std::int32_t> truth,
                                               std::span<const std::int32_t> found,
                                               double tolerance = 0.8,
                                               std::uint64_t min_points = 500,
                                               std::span<const std::uint8_t> scored = {});

}  // namespace surfgrow::eval
