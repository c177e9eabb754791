// The environment as spheres at the home points (paper section 5.5), with fast proximity queries.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/surface.hpp"
#include "surfgrow/robot/collision_shapes.hpp"

namespace surfgrow {

/// The answer to a proximity query.
struct Proximity {
    /// Signed clearance to the nearest environment sphere: the distance between the surfaces,
    /// negative when penetrating. +infinity when the environment is empty.
    double clearance = kNoClearanceLimit;
    /// Id of that sphere (its position in the environment; for surfaces, the surface id); -1 when
    /// the environment is empty. Among spheres at exactly the same clearance, the lowest id.
    std::int64_t nearest = -1;
};

/// Environment spheres in a bounding-volume hierarchy.
///
/// Paper 5.5: "represent the robot arm and surfaces with a set of spheres with center at the home
/// point and radius of mu". The hierarchy is a binary tree of float boxes of the centres (rounded
/// outwards) with the largest radius below each, split at the median of the longest axis, leaves of
/// up to 4 spheres. Queries descend nearest box first and prune boxes that cannot beat the best so
/// far, so a query costs about log(n) box tests plus a few exact distances. Queries are const and
/// thread-safe; results do not depend on the tree's shape (ties go to the lowest id).
class CollisionSpheres {
  public:
    CollisionSpheres() = default;
    /// Throws Error(kInvalidParameter) naming the first sphere with a non-finite centre or a
    /// radius that is negative or not finite.
    explicit CollisionSpheres(std::vector<Sphere> spheres);

    /// One sphere per surface: centre at its home point, radius its neighbourhood radius (mu, or
    /// larger where the radius adapted). Sphere id = surface id.
    [[nodiscard]] static CollisionSpheres from_surfaces(std::span<const Surface> surfaces);

    [[nodiscard]] std::size_t size() const { return spheres_.size(); }
    [[nodiscard]] bool empty() const { return spheres_.empty(); }
    [[nodiscard]] const std::vector<Sphere>& spheres() const { return spheres_; }
    [[nodiscard]] double max_radius() const { return max_radius_; }

    /// The nearest environment sphere to a query shape and the signed clearance to it.
    /// Throws Error(kInvalidParameter) for a shape with non-finite values or a negative radius.
    [[nodiscard]] Proximity nearest(const Sphere& query) const;
    [[nodiscard]] Proximity nearest(const Capsule& query) const;

    /// nearest(query).clearance.
    [[nodiscard]] double min_distance(const Sphere& query) const {
        return nearest(query).clearance;
    }
    [[nodiscard]] double min_distance(const Capsule& query) const {
        return nearest(query).clearance;
    }

    /// Whether any environment sphere is closer than `tolerance` to the query (clearance <
    /// tolerance): with tolerance 0, touching is clear and any overlap collides; a positive
    /// tolerance is a safety margin. Stops at the first such sphere. Throws like nearest(), and
    /// for a non-finite tolerance.
    [[nodiscard]] bool collides(const Sphere& query, double tolerance = 0.0) const;
    [[nodiscard]] bool collides(const Capsule& query, double tolerance = 0.0) const;

    /// Every environment sphere with clearance < tolerance, ascending ids.
    [[nodiscard]] std::vector<std::uint32_t> colliding(const Capsule& query,
                                                       double tolerance = 0.0) const;

    /// Depth of the tree (for tests and diagnostics).
    [[nodiscard]] int depth() const { return depth_; }

  private:
    struct Node {
        float lo[3];  ///< box of the centres, rounded outwards
        float hi[3];
        float rmax = 0;           ///< largest radius, rounded up
        std::uint32_t first = 0;  ///< leaf: first entry in leaf_; inner: index of the right child
        std::uint32_t count = 0;  ///< leaf: number of spheres; inner: 0 (left child is next)
    };
    enum class Mode { kNearest, kAny, kAll };
    std::uint32_t build(std::vector<std::uint32_t>& order, std::uint32_t begin, std::uint32_t end,
                        int depth);
    template <Mode kMode, bool kPoint>
    Proximity query(const Capsule& q, double tolerance, std::vector<std::uint32_t>* all) const;
    template <Mode kMode>
    Proximity dispatch(const Capsule& q, double tolerance, std::vector<std::uint32_t>* all) const;

    std::vector<Sphere> spheres_;         // by id
    std::vector<Sphere> leaf_;            // in leaf order
    std::vector<std::uint32_t> leaf_id_;  // id of each leaf_ entry
    std::vector<Node> nodes_;             // depth first; root at 0
    double max_radius_ = 0.0;
    int depth_ = 0;
};

}  // namespace surfgrow
