// Scoring a segmentation of a cloud against ground truth: over- and under-segmentation counts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow::eval {

/// When an overlap of a true face and a found segment counts.
struct SegmentationScoreConfig {
    /// A face or segment with fewer labelled points (counted where both labellings have one) is
    /// left out: bolt heads and slivers say little about merging.
    std::uint64_t min_points = 200;
    /// An overlap counts when it holds at least this share of the face's points (for
    /// over-segmentation) or of the segment's points (for under-segmentation)...
    double min_share = 0.05;
    std::uint64_t min_overlap_points = 50;  ///< ... and at least this many points
};

struct SegmentationScore {
    std::uint64_t faces = 0;            ///< true faces scored (>= min_points)
    std::uint64_t segments = 0;         ///< found segments scored (>= min_points)
    std::uint64_t over_segmented = 0;   ///< faces split across 2 or more segments
    std::uint64_t under_segmented = 0;  ///< segments spanning 2 or more faces
    std::uint64_t one_to_one = 0;       ///< faces whose points lie in a single segment
    std::uint64_t missed = 0;           ///< faces with no counting overlap at all
    double points_in_best = 0.0;  ///< share of the scored faces' points in their largest segment
    std::vector<std::int32_t> over_faces;      ///< the over-segmented face ids
    std::vector<std::int32_t> under_segments;  ///< the under-segmented segment ids
};

/// Compares `found` (segment id per point, -1 none) with `truth` (face id per point, -1 none) over
/// the points labelled in both. Throws Error(kInvalidParameter) if the sizes differ.
[[nodiscard]] SegmentationScore score_segmentation(std::span<const std::int32_t> truth,
                                                   std::span<const std::int32_t> found,
                                                   const SegmentationScoreConfig& config = {});

/// Splits each true face into its connected pieces: points of one face closer than `link` are
/// in one piece. Returns a piece id per point (-1 where truth is -1), numbered by first point.
/// A face interrupted by an occluder (a web between stiffeners) becomes several pieces, which a
/// segmentation that merges only neighbouring patches cannot be asked to join.
[[nodiscard]] std::vector<std::int32_t> truth_pieces(std::span<const Vec3f> points,
                                                     std::span<const std::int32_t> truth,
                                                     double link);

}  // namespace surfgrow::eval
