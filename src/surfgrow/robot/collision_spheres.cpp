#include "surfgrow/robot/collision_spheres.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr int kMaxDepth = 60;  // median splits: depth is about log2(n / 4)

// A float at or below v, one more ulp down: the float box always contains the double one, with
// room to spare for the rounding of the distance computations.
float round_down(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return std::nextafter(f, -std::numeric_limits<float>::infinity());
}

float round_up(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return std::nextafter(f, std::numeric_limits<float>::infinity());
}

void check_query(const Capsule& q) {
    if (!is_valid(q))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"collision query: a shape needs finite coordinates and a finite radius >= "
                         "0, got radius ",
                         num(q.radius)}));
}

void check_tolerance(double tolerance) {
    if (!std::isfinite(tolerance))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"collision query: the tolerance must be finite, got ", num(tolerance)}));
}

}  // namespace

CollisionSpheres::CollisionSpheres(std::vector<Sphere> spheres) : spheres_(std::move(spheres)) {
    if (spheres_.size() >= std::numeric_limits<std::uint32_t>::max() / 2)
        throw Error(ErrorCode::kCloudTooLarge, "collision spheres: too many spheres");
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
        if (!is_valid(spheres_[i]))
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"collision sphere ", std::to_string(i),
                             " needs a finite centre and a finite radius >= 0, got radius ",
                             num(spheres_[i].radius)}));
        max_radius_ = std::max(max_radius_, spheres_[i].radius);
    }
    if (spheres_.empty()) return;
    std::vector<std::uint32_t> order(spheres_.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    nodes_.reserve(2 * (spheres_.size() / kLeafSize + 1));
    leaf_.reserve(spheres_.size());
    leaf_id_.reserve(spheres_.size());
    build(order, 0, static_cast<std::uint32_t>(order.size()), 1);
}

CollisionSpheres CollisionSpheres::from_surfaces(std::span<const Surface> surfaces) {
    std::vector<Sphere> spheres(surfaces.size());
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        spheres[i] = {surfaces[i].home, surfaces[i].radius};
    return CollisionSpheres(std::move(spheres));
}

std::uint32_t CollisionSpheres::build(std::vector<std::uint32_t>& order, std::uint32_t begin,
                                      std::uint32_t end, int depth) {
    depth_ = std::max(depth_, depth);
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Aabb centres;
    double rmax = 0;
    for (std::uint32_t k = begin; k < end; ++k) {
        const Sphere& s = spheres_[order[k]];
        centres.add(s.centre);
        rmax = std::max(rmax, s.radius);
    }
    for (int a = 0; a < 3; ++a) {
        nodes_[index].lo[a] = round_down(centres.min[a]);
        nodes_[index].hi[a] = round_up(centres.max[a]);
    }
    nodes_[index].rmax = round_up(rmax);
    if (end - begin <= kLeafSize || depth >= kMaxDepth) {
        nodes_[index].first = static_cast<std::uint32_t>(leaf_.size());
        nodes_[index].count = end - begin;
        for (std::uint32_t k = begin; k < end; ++k) {
            leaf_.push_back(spheres_[order[k]]);
            leaf_id_.push_back(order[k]);
        }
        return index;
    }
    int axis = 0;
    centres.size().maxCoeff(&axis);
    const std::uint32_t mid = begin + (end - begin) / 2;
    // (coordinate, id) is a total order, so the halves are the same sets on every platform.
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](std::uint32_t i, std::uint32_t j) {
                         const double ci = spheres_[i].centre[axis], cj = spheres_[j].centre[axis];
                         return ci < cj || (ci == cj && i < j);
                     });
    build(order, begin, mid, depth + 1);
    const std::uint32_t right = build(order, mid, end, depth + 1);
    nodes_[index].first = right;
    return index;
}

template <CollisionSpheres::Mode kMode, bool kPoint>
Proximity CollisionSpheres::query(const Capsule& q, double tolerance,
                                  std::vector<std::uint32_t>* all) const {
    Proximity best;
    if (nodes_.empty()) return best;
    const Vec3d smin = q.a.cwiseMin(q.b), smax = q.a.cwiseMax(q.b);
    // Lower bound on the clearance of any sphere in node n: the distance from the segment to the
    // box of n's centres, less n's largest radius and the query's. The distance is bounded below
    // by the gap between the segment's box and n's box (exact for a sphere query), and for a
    // capsule also by the distance to n's box centre less its half diagonal, when the first is
    // not enough to prune.
    auto bound = [&](const Node& n, double limit) {
        double g2 = 0;
        for (int a = 0; a < 3; ++a) {
            const double lo = n.lo[a], hi = n.hi[a];
            const double gap = std::max(std::max(lo - smax[a], smin[a] - hi), 0.0);
            g2 += gap * gap;
        }
        const double pad = q.radius + static_cast<double>(n.rmax);
        double lb = std::sqrt(g2) - pad;
        if constexpr (!kPoint) {
            if (lb <= limit) {
                Vec3d centre;
                double h2 = 0;
                for (int a = 0; a < 3; ++a) {
                    const double lo = n.lo[a], hi = n.hi[a];
                    centre[a] = 0.5 * (lo + hi);
                    h2 += (hi - lo) * (hi - lo);
                }
                const double ball = point_segment_distance(centre, q.a, q.b) - 0.5 * std::sqrt(h2);
                if (std::isfinite(ball)) lb = std::max(lb, ball - pad);
            }
        }
        return lb;
    };
    // Nearest: prune what cannot beat or tie the best; any/all: what cannot come under tolerance.
    auto limit = [&] { return kMode == Mode::kNearest ? best.clearance : tolerance; };
    auto pruned = [&](double lb) {
        return kMode == Mode::kNearest ? lb > best.clearance : lb >= tolerance;
    };

    std::array<std::uint32_t, kMaxDepth + 2> stack_node{};
    std::array<double, kMaxDepth + 2> stack_bound{};
    std::size_t top = 0;
    const double root_bound = bound(nodes_[0], limit());
    if (pruned(root_bound)) return best;
    stack_node[0] = 0;
    stack_bound[0] = root_bound;
    top = 1;
    while (top > 0) {
        --top;
        if (pruned(stack_bound[top])) continue;
        std::uint32_t n = stack_node[top];
        while (true) {
            const Node& node = nodes_[n];
            if (node.count > 0) {
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                    const double d = clearance(leaf_[k], q);
                    const std::uint32_t id = leaf_id_[k];
                    if constexpr (kMode == Mode::kNearest) {
                        if (d < best.clearance ||
                            (d == best.clearance && std::int64_t{id} < best.nearest)) {
                            best.clearance = d;
                            best.nearest = id;
                        }
                    } else if (d < tolerance) {
                        if constexpr (kMode == Mode::kAny) return {d, id};
                        all->push_back(id);
                    }
                }
                break;
            }
            const std::uint32_t left = n + 1, right = node.first;
            const double bl = bound(nodes_[left], limit()), br = bound(nodes_[right], limit());
            const bool pl = pruned(bl), pr = pruned(br);
            if (pl && pr) break;
            if (pl || pr) {
                n = pl ? right : left;
                continue;
            }
            // Descend into the nearer child now; the other waits on the stack.
            const bool left_first = bl <= br;
            stack_node[top] = left_first ? right : left;
            stack_bound[top] = left_first ? br : bl;
            ++top;
            n = left_first ? left : right;
        }
    }
    return best;
}

template <CollisionSpheres::Mode kMode>
Proximity CollisionSpheres::dispatch(const Capsule& q, double tolerance,
                                     std::vector<std::uint32_t>* all) const {
    return q.a == q.b ? query<kMode, true>(q, tolerance, all)
                      : query<kMode, false>(q, tolerance, all);
}

Proximity CollisionSpheres::nearest(const Sphere& query_sphere) const {
    return nearest(Capsule::of(query_sphere));
}

Proximity CollisionSpheres::nearest(const Capsule& q) const {
    check_query(q);
    return dispatch<Mode::kNearest>(q, 0.0, nullptr);
}

bool CollisionSpheres::collides(const Sphere& query_sphere, double tolerance) const {
    return collides(Capsule::of(query_sphere), tolerance);
}

bool CollisionSpheres::collides(const Capsule& q, double tolerance) const {
    check_query(q);
    check_tolerance(tolerance);
    return dispatch<Mode::kAny>(q, tolerance, nullptr).nearest >= 0;
}

std::vector<std::uint32_t> CollisionSpheres::colliding(const Capsule& q, double tolerance) const {
    check_query(q);
    check_tolerance(tolerance);
    std::vector<std::uint32_t> ids;
    dispatch<Mode::kAll>(q, tolerance, &ids);
    std::sort(ids.begin(), ids.end());
    return ids;
}

}  // namespace surfgrow
