// A scene to scan: primitives with ground-truth face ids, and the nearest-hit ray caster.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/scanner/pose.hpp"
#include "surfgrow/scanner/primitives.hpp"
#include "surfgrow/scanner/ray.hpp"

namespace surfgrow::scanner {

/// Where a scene suggests scanning from: `count` poses spaced by step_m along a line centred on
/// home (see scan_poses()).
struct ScanPath {
    Pose home = Pose::Identity();     ///< sensor-to-world pose of the middle scan
    Vec3d step_m = Vec3d(0.5, 0, 0);  ///< offset between consecutive scans, world frame
};

/// What a scene is made of, as a user writes it (scene files, built-in scenes).
struct SceneDescription {
    std::string name;
    std::vector<Primitive> primitives;
    ScanPath scanner;
};

/// `count` scan poses: home translated by (k - (count - 1) / 2) * step_m for k = 0..count-1, all
/// with home's orientation. Throws Error(kInvalidParameter) unless 1 <= count <= 1000.
[[nodiscard]] std::vector<Pose> scan_poses(const ScanPath& path, int count);

/// An immutable scene with a bounding-volume hierarchy over its primitives.
///
/// Faces are numbered 0, 1, 2, ... in primitive order (a rectangle has 1 face, a box 6, a capped
/// cylinder 3, an open one 1); faces()[id].id == id.
class Scene {
  public:
    /// Validates every primitive (finite values under 1e6 m, positive sizes, perpendicular
    /// rectangle axes, a proper rotation for boxes, a cylinder of positive length) and throws
    /// Error(kInvalidParameter) naming the primitive (index and name) and the problem.
    explicit Scene(SceneDescription description);

    [[nodiscard]] const SceneDescription& description() const { return description_; }
    [[nodiscard]] const std::vector<Face>& faces() const { return faces_; }
    [[nodiscard]] std::size_t primitive_count() const { return description_.primitives.size(); }
    /// Bounds of all primitives (empty for an empty scene).
    [[nodiscard]] const Aabb& bounds() const { return bounds_; }

    /// The nearest hit with 1e-6 m < t <= t_max, or none. Surfaces are seen from both sides; a ray
    /// that starts inside a solid hits its faces from inside. Thread-safe.
    [[nodiscard]] std::optional<Hit> intersect(const Ray& ray, double t_max) const;
    /// Same as above without the optional; returns false when nothing is hit.
    bool intersect(const Ray& ray, double t_max, Hit& hit) const;

    /// Outward normal of face `face_id` at point `p` (see Face::normal_at). Throws
    /// Error(kInvalidParameter) for an unknown id.
    [[nodiscard]] Vec3d normal_at(std::int32_t face_id, const Vec3d& p) const;

    /// The faces that are planes (rectangles, box faces, cylinder caps): the ground-truth planes.
    [[nodiscard]] std::vector<Face> planar_faces() const;

  private:
    /// A primitive prepared for ray casting.
    struct Compiled {
        enum class Kind : std::uint8_t { kRectangle, kBox, kCylinder };
        Kind kind = Kind::kRectangle;
        bool capped = false;
        std::int32_t first_face = 0;
        Vec3d origin = Vec3d::Zero();    ///< rectangle / box centre; cylinder base centre
        Mat3d axes = Mat3d::Identity();  ///< rectangle: u, v, n; box: its axes; cylinder: axis
        Vec3d size = Vec3d::Zero();      ///< rectangle: half u, half v; box: half sizes; cylinder:
                                         ///< radius, length
    };
    static Compiled compile(const Primitive& primitive, std::int32_t first_face);
    bool hit_primitive(const Compiled& c, const Ray& ray, double t_max, Hit& hit) const;

    struct Node {
        Vec3d lo = Vec3d::Zero();
        Vec3d hi = Vec3d::Zero();
        std::int32_t first = 0;  ///< leaf: first entry in order_; inner: index of left child
        std::int32_t count = 0;  ///< leaf: number of primitives; inner: 0
    };
    void build_bvh();

    SceneDescription description_;
    std::vector<Face> faces_;
    std::vector<Compiled> compiled_;
    std::vector<std::int32_t> order_;
    std::vector<Node> nodes_;
    Aabb bounds_;
};

}  // namespace surfgrow::scanner
