// A read-only look at a point cloud held elsewhere: what every stage reads.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow {

/// The fields of a PointCloud as spans over memory the caller owns: a PointCloud, a numpy array,
/// a ROS message's buffer. The stages take one, so a cloud held in any of these is read in place,
/// never copied; a PointCloud converts to it implicitly. The memory must outlive the call (and not
/// change during it); no stage keeps a view after it returns.
///
/// `points` is (N) x,y,z floats back to back, as in an (N, 3) C-ordered float32 array.
struct CloudView {
    std::span<const Vec3f> points;  ///< positions relative to `offset`, in input order
    Vec3d offset = Vec3d::Zero();   ///< add to a position to get file coordinates
    std::optional<Vec3d> viewpoint;
    std::span<const std::uint32_t> scan_index;  ///< see PointCloud: empty, or one per point
    std::span<const Vec3d> scan_origins;
    std::span<const std::int32_t> labels;
    std::span<const Vec3f> normals;

    CloudView() = default;
    explicit CloudView(std::span<const Vec3f> p) : points(p) {}
    // Implicit: every stage that took a PointCloud takes one as before. Out of line: inlined
    // into a caller holding an empty PointCloud, GCC's -O1 (the sanitizer builds) warns that the
    // empty optional's storage may be read.
    CloudView(const PointCloud& c);  // NOLINT(google-explicit-constructor)

    [[nodiscard]] std::size_t size() const { return points.size(); }
    [[nodiscard]] bool empty() const { return points.empty(); }
    [[nodiscard]] bool has_scan_index() const { return one_per_point(scan_index.size(), size()); }
    [[nodiscard]] bool has_labels() const { return one_per_point(labels.size(), size()); }
    [[nodiscard]] bool has_normals() const { return one_per_point(normals.size(), size()); }
};

/// A PointCloud that owns a copy of what `view` shows.
[[nodiscard]] inline PointCloud to_point_cloud(const CloudView& view) {
    PointCloud c;
    c.points.assign(view.points.begin(), view.points.end());
    c.offset = view.offset;
    c.viewpoint = view.viewpoint;
    c.scan_index.assign(view.scan_index.begin(), view.scan_index.end());
    c.scan_origins.assign(view.scan_origins.begin(), view.scan_origins.end());
    c.labels.assign(view.labels.begin(), view.labels.end());
    c.normals.assign(view.normals.begin(), view.normals.end());
    return c;
}

}  // namespace surfgrow
