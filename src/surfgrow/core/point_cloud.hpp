// The point cloud every stage works on: positions plus what is known about the scans.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// Whether an optional per-point field of `entries` values holds one per point: empty means
/// unknown, and any other count is not trusted (PointCloud and CloudView alike).
[[nodiscard]] constexpr bool one_per_point(std::size_t entries, std::size_t points) {
    return entries != 0 && entries == points;
}

/// A point cloud in its own units (metres for ROS/PCL/Open3D clouds, or whatever the file holds).
///
/// Positions are float, as in the sensors' own formats. Georeferenced clouds keep their precision
/// through `offset`: readers subtract a large common offset and writers add it back, so every
/// coordinate stored here is small. Points may be NaN/Inf (sensors write them for missed
/// returns): stages skip them and every per-point output still has one entry per stored point.
struct PointCloud {
    std::vector<Vec3f> points;     ///< positions relative to `offset`, in input order
    Vec3d offset = Vec3d::Zero();  ///< add to a position to get file coordinates

    /// Sensor origin (relative to `offset`) when one is known for the whole cloud.
    std::optional<Vec3d> viewpoint;

    /// Fused clouds: for each point the index of the scan it came from (empty if unknown), and
    /// for each scan its sensor origin (relative to `offset`). Normals can then face their sensor.
    std::vector<uint32_t> scan_index;
    std::vector<Vec3d> scan_origins;

    /// Optional per-point integer label from the file (ground-truth primitive id, segment label).
    std::vector<int32_t> labels;

    /// Optional per-point normal from the file or the caller (PLY nx ny nz, PCD normal_x ...):
    /// empty when unknown, else one per point. Only carried through reading and writing; the
    /// growing estimates its own.
    std::vector<Vec3f> normals;

    [[nodiscard]] std::size_t size() const { return points.size(); }
    [[nodiscard]] bool empty() const { return points.empty(); }
    [[nodiscard]] bool has_scan_index() const { return one_per_point(scan_index.size(), size()); }
    [[nodiscard]] bool has_labels() const { return one_per_point(labels.size(), size()); }
    [[nodiscard]] bool has_normals() const { return one_per_point(normals.size(), size()); }
};

}  // namespace surfgrow
