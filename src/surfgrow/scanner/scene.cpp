#include "surfgrow/scanner/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

namespace {

constexpr double kTMin = 1e-6;     // hits closer than this are the ray's own surface
constexpr double kMaxCoord = 1e6;  // metres; anything larger is a unit mistake
constexpr double kAxisTolerance = 1e-6;
constexpr std::size_t kMaxPrimitives = 1'000'000;

[[noreturn]] void bad_primitive(std::size_t index, const Primitive& p, std::string_view why) {
    const std::string label =
        p.name.empty() ? std::string() : cat({" '", std::string_view(p.name), "'"});
    throw Error(ErrorCode::kInvalidParameter,
                cat({"primitive ", std::to_string(index), label, ": ", why}));
}

bool finite_point(const Vec3d& v) {
    return v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxCoord;
}
bool positive_size(double v) {
    return std::isfinite(v) && v > 0.0 && v <= kMaxCoord;
}

void validate_primitive(std::size_t i, const Primitive& p) {
    if (const auto* r = std::get_if<Rectangle>(&p.shape)) {
        if (!finite_point(r->center)) bad_primitive(i, p, "rectangle centre is not finite");
        if (!r->u_axis.allFinite() || !r->v_axis.allFinite() || r->u_axis.norm() < 1e-12 ||
            r->v_axis.norm() < 1e-12)
            bad_primitive(i, p, "rectangle axes must be finite non-zero vectors");
        const double c = r->u_axis.normalized().dot(r->v_axis.normalized());
        if (std::abs(c) > kAxisTolerance)
            bad_primitive(i, p,
                          cat({"rectangle axes are not perpendicular (cosine ", num(c), ")"}));
        if (!positive_size(r->half_u_m) || !positive_size(r->half_v_m))
            bad_primitive(i, p,
                          cat({"rectangle size must be positive, got ", num(2 * r->half_u_m), " x ",
                               num(2 * r->half_v_m), " m"}));
    } else if (const auto* b = std::get_if<Box>(&p.shape)) {
        if (!finite_point(b->center)) bad_primitive(i, p, "box centre is not finite");
        const Mat3d& m = b->rotation;
        if (!m.allFinite() ||
            (m.transpose() * m - Mat3d::Identity()).cwiseAbs().maxCoeff() > kAxisTolerance ||
            m.determinant() < 0.0)
            bad_primitive(i, p, "box rotation is not a rotation matrix");
        const Vec3d& h = b->half_size_m;
        if (!positive_size(h.x()) || !positive_size(h.y()) || !positive_size(h.z()))
            bad_primitive(i, p,
                          cat({"box size must be positive, got ", num(2 * h.x()), " x ",
                               num(2 * h.y()), " x ", num(2 * h.z()), " m"}));
    } else {
        const auto& c = std::get<Cylinder>(p.shape);
        if (!finite_point(c.base) || !finite_point(c.top))
            bad_primitive(i, p, "cylinder end points are not finite");
        if (!((c.top - c.base).norm() > 1e-9))
            bad_primitive(i, p, "cylinder base and top coincide (zero length)");
        if (!positive_size(c.radius_m))
            bad_primitive(i, p, cat({"cylinder radius must be positive, got ", num(c.radius_m)}));
    }
}

Vec3d any_perpendicular(const Vec3d& a) {
    const Vec3d helper = std::abs(a.x()) < 0.9 ? Vec3d::UnitX() : Vec3d::UnitY();
    return a.cross(helper).normalized();
}

Face make_face(std::int32_t id, std::int32_t prim, FaceKind kind, const Vec3d& center,
               const Vec3d& normal, const Vec3d& u, const Vec3d& v, double hu, double hv) {
    return {id, prim, kind, center, normal, u, v, hu, hv};
}

}  // namespace

std::vector<Pose> scan_poses(const ScanPath& path, int count) {
    if (count < 1 || count > 1000)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"number of scan poses must be in 1..1000, got ", std::to_string(count)}));
    std::vector<Pose> poses;
    for (int k = 0; k < count; ++k) {
        Pose p = path.home;
        p.translation() += (k - 0.5 * (count - 1)) * path.step_m;
        poses.push_back(p);
    }
    return poses;
}

Scene::Compiled Scene::compile(const Primitive& primitive, std::int32_t first_face) {
    Compiled c;
    c.first_face = first_face;
    if (const auto* r = std::get_if<Rectangle>(&primitive.shape)) {
        const Vec3d u = r->u_axis.normalized();
        const Vec3d v = (r->v_axis - r->v_axis.dot(u) * u).normalized();
        c.kind = Compiled::Kind::kRectangle;
        c.origin = r->center;
        c.axes.col(0) = u;
        c.axes.col(1) = v;
        c.axes.col(2) = u.cross(v);
        c.size = Vec3d(r->half_u_m, r->half_v_m, 0.0);
    } else if (const auto* b = std::get_if<Box>(&primitive.shape)) {
        c.kind = Compiled::Kind::kBox;
        c.origin = b->center;
        c.axes = b->rotation;
        c.size = b->half_size_m;
    } else {
        const auto& cy = std::get<Cylinder>(primitive.shape);
        const Vec3d axis = cy.top - cy.base;
        c.kind = Compiled::Kind::kCylinder;
        c.capped = cy.capped;
        c.origin = cy.base;
        c.axes.col(0) = axis.normalized();
        c.axes.col(1) = any_perpendicular(c.axes.col(0));
        c.axes.col(2) = c.axes.col(0).cross(c.axes.col(1));
        c.size = Vec3d(cy.radius_m, axis.norm(), 0.0);
    }
    return c;
}

Scene::Scene(SceneDescription description) : description_(std::move(description)) {
    const auto& prims = description_.primitives;
    if (prims.size() > kMaxPrimitives)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"a scene may hold at most 1000000 primitives, got ",
                         std::to_string(prims.size())}));
    check_rigid(description_.scanner.home);
    if (!description_.scanner.step_m.allFinite())
        throw Error(ErrorCode::kInvalidParameter, "scan path step is not finite");
    for (std::size_t i = 0; i < prims.size(); ++i) {
        validate_primitive(i, prims[i]);
        const auto id = static_cast<std::int32_t>(faces_.size());
        const auto pi = static_cast<std::int32_t>(i);
        const Compiled c = compile(prims[i], id);
        compiled_.push_back(c);
        const Mat3d& ax = c.axes;
        switch (c.kind) {
            case Compiled::Kind::kRectangle:
                faces_.push_back(make_face(id, pi, FaceKind::kRectangle, c.origin, ax.col(2),
                                           ax.col(0), ax.col(1), c.size.x(), c.size.y()));
                break;
            case Compiled::Kind::kBox: {
                // +x, -x, +y, -y, +z, -z; (u, v) chosen so that u x v is the outward normal.
                static constexpr std::array<std::array<int, 2>, 3> uv{{{1, 2}, {2, 0}, {0, 1}}};
                for (int f = 0; f < 6; ++f) {
                    const int a = f / 2;
                    const double s = (f % 2 == 0) ? 1.0 : -1.0;
                    int ui = uv[a][0], vi = uv[a][1];
                    if (s < 0) std::swap(ui, vi);
                    faces_.push_back(make_face(id + f, pi, FaceKind::kRectangle,
                                               c.origin + s * c.size[a] * ax.col(a), s * ax.col(a),
                                               ax.col(ui), ax.col(vi), c.size[ui], c.size[vi]));
                }
                break;
            }
            case Compiled::Kind::kCylinder: {
                const double r = c.size.x(), len = c.size.y();
                faces_.push_back(make_face(id, pi, FaceKind::kCylinder,
                                           c.origin + 0.5 * len * ax.col(0), ax.col(0), ax.col(1),
                                           ax.col(2), r, 0.5 * len));
                if (c.capped) {
                    faces_.push_back(make_face(id + 1, pi, FaceKind::kDisc, c.origin, -ax.col(0),
                                               ax.col(2), ax.col(1), r, r));
                    faces_.push_back(make_face(id + 2, pi, FaceKind::kDisc,
                                               c.origin + len * ax.col(0), ax.col(0), ax.col(1),
                                               ax.col(2), r, r));
                }
                break;
            }
        }
    }
    build_bvh();
}

namespace {

// Axis-aligned bounds of a compiled primitive, padded so flat rectangles have some thickness.
template <class C>
Aabb primitive_bounds(const C& c) {
    Vec3d lo, hi;
    const Mat3d& ax = c.axes;
    using Kind = typename C::Kind;
    if (c.kind == Kind::kCylinder) {
        const Vec3d a = ax.col(0);
        const Vec3d top = c.origin + c.size.y() * a;
        const Vec3d ext =
            c.size.x() * (Vec3d::Ones() - a.cwiseProduct(a)).cwiseMax(0.0).cwiseSqrt();
        lo = c.origin.cwiseMin(top) - ext;
        hi = c.origin.cwiseMax(top) + ext;
    } else {
        const Vec3d ext = ax.cwiseAbs() * c.size;
        lo = c.origin - ext;
        hi = c.origin + ext;
    }
    Aabb box;
    box.add(lo - Vec3d::Constant(1e-7));
    box.add(hi + Vec3d::Constant(1e-7));
    return box;
}

// Slab test of a ray against a box for t in [0, t_max]; returns the entry distance. `inv` holds
// 1/direction with zero components replaced by a huge finite value, so no 0 * inf NaN arises.
inline bool ray_box(const Vec3d& lo, const Vec3d& hi, const Vec3d& origin, const Vec3d& inv,
                    double t_max, double& t_enter) {
    const Vec3d ta = (lo - origin).cwiseProduct(inv);
    const Vec3d tb = (hi - origin).cwiseProduct(inv);
    const double t0 = std::max(ta.cwiseMin(tb).maxCoeff(), 0.0);
    const double t1 = std::min(ta.cwiseMax(tb).minCoeff(), t_max);
    t_enter = t0;
    return t0 <= t1;
}

}  // namespace

namespace {

double half_area(const Aabb& b) {
    if (b.empty()) return 0.0;
    const Vec3d e = b.size();
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

// Binned surface-area-heuristic split of order[begin, end): the partition point, or `end` when
// keeping a leaf is cheaper (or nothing can be split).
std::size_t sah_partition(std::vector<std::int32_t>& order, std::size_t begin, std::size_t end,
                          const std::vector<Aabb>& boxes, const std::vector<Vec3d>& centres,
                          const Aabb& box, const Aabb& cbox) {
    constexpr int kBins = 16;
    constexpr double kTraversalCost = 1.0;  // relative to one primitive test
    const std::size_t count = end - begin;
    double best_cost = static_cast<double>(count);  // a leaf
    int best_axis = -1, best_bin = 0;
    const double parent_area = std::max(half_area(box), 1e-300);
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = cbox.min[axis], extent = cbox.max[axis] - cbox.min[axis];
        if (!(extent > 0.0)) continue;
        auto bin_of = [&](std::int32_t p) {
            const int b = static_cast<int>(kBins * (centres[p][axis] - lo) / extent);
            return std::clamp(b, 0, kBins - 1);
        };
        std::array<Aabb, kBins> bin_box{};
        std::array<std::size_t, kBins> bin_count{};
        for (std::size_t i = begin; i < end; ++i) {
            const int b = bin_of(order[i]);
            bin_box[b].add(boxes[order[i]].min);
            bin_box[b].add(boxes[order[i]].max);
            ++bin_count[b];
        }
        // right_area[b], right_count[b]: bins b..kBins-1.
        std::array<double, kBins> right_area{};
        std::array<std::size_t, kBins> right_count{};
        Aabb acc;
        std::size_t n = 0;
        for (int b = kBins - 1; b > 0; --b) {
            if (!bin_box[b].empty()) acc.add(bin_box[b].min), acc.add(bin_box[b].max);
            n += bin_count[b];
            right_area[b] = half_area(acc);
            right_count[b] = n;
        }
        Aabb left;
        std::size_t nl = 0;
        for (int b = 1; b < kBins; ++b) {
            if (!bin_box[b - 1].empty()) left.add(bin_box[b - 1].min), left.add(bin_box[b - 1].max);
            nl += bin_count[b - 1];
            if (nl == 0 || right_count[b] == 0) continue;
            const double cost =
                kTraversalCost + (half_area(left) * static_cast<double>(nl) +
                                  right_area[b] * static_cast<double>(right_count[b])) /
                                     parent_area;
            if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
        }
    }
    if (best_axis < 0) {
        if (count <= 4) return end;
        // Identical centres: split by position in the list to keep leaves small.
        return begin + count / 2;
    }
    const double lo = cbox.min[best_axis], extent = cbox.max[best_axis] - cbox.min[best_axis];
    const auto mid = std::stable_partition(
        order.begin() + static_cast<std::ptrdiff_t>(begin),
        order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::int32_t p) {
            const int b = static_cast<int>(kBins * (centres[p][best_axis] - lo) / extent);
            return std::clamp(b, 0, kBins - 1) < best_bin;
        });
    return static_cast<std::size_t>(mid - order.begin());
}

}  // namespace

void Scene::build_bvh() {
    const std::size_t n = compiled_.size();
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    std::vector<Aabb> boxes;
    std::vector<Vec3d> centres;
    for (const Compiled& c : compiled_) {
        boxes.push_back(primitive_bounds(c));
        centres.push_back(boxes.back().center());
        bounds_.add(boxes.back().min);
        bounds_.add(boxes.back().max);
    }
    if (n == 0) return;
    nodes_.reserve(2 * n);
    nodes_.push_back({});
    // Iterative top-down build: (node index, begin, end) ranges of order_.
    struct Task {
        std::size_t node, begin, end;
    };
    std::vector<Task> tasks{{0, 0, n}};
    while (!tasks.empty()) {
        const Task task = tasks.back();
        tasks.pop_back();
        Aabb box, cbox;
        for (std::size_t i = task.begin; i < task.end; ++i) {
            box.add(boxes[order_[i]].min);
            box.add(boxes[order_[i]].max);
            cbox.add(centres[order_[i]]);
        }
        nodes_[task.node].lo = box.min;
        nodes_[task.node].hi = box.max;
        const std::size_t count = task.end - task.begin;
        const std::size_t mid =
            count <= 1 ? task.end
                       : sah_partition(order_, task.begin, task.end, boxes, centres, box, cbox);
        if (mid == task.end || mid == task.begin) {
            nodes_[task.node].first = static_cast<std::int32_t>(task.begin);
            nodes_[task.node].count = static_cast<std::int32_t>(count);
            continue;
        }
        const std::size_t left = nodes_.size();
        nodes_[task.node].first = static_cast<std::int32_t>(left);
        nodes_[task.node].count = 0;
        nodes_.push_back({});
        nodes_.push_back({});
        tasks.push_back({left, task.begin, mid});
        tasks.push_back({left + 1, mid, task.end});
    }
}

bool Scene::hit_primitive(const Compiled& c, const Ray& ray, double t_max, Hit& hit) const {
    const Vec3d& d = ray.direction;
    switch (c.kind) {
        case Compiled::Kind::kRectangle: {
            const Vec3d n = c.axes.col(2);
            const double denom = n.dot(d);
            if (std::abs(denom) < 1e-15) return false;
            const double t = n.dot(c.origin - ray.origin) / denom;
            if (!(t > kTMin && t <= t_max)) return false;
            const Vec3d w = ray.origin + t * d - c.origin;
            if (std::abs(w.dot(c.axes.col(0))) > c.size.x() ||
                std::abs(w.dot(c.axes.col(1))) > c.size.y())
                return false;
            hit.t = t;
            hit.face_id = c.first_face;
            hit.normal = denom < 0.0 ? n : Vec3d(-n);
            return true;
        }
        case Compiled::Kind::kBox: {
            const Vec3d o = c.axes.transpose() * (ray.origin - c.origin);
            const Vec3d dl = c.axes.transpose() * d;
            double t0 = -std::numeric_limits<double>::infinity();
            double t1 = std::numeric_limits<double>::infinity();
            int a0 = 0, a1 = 0;
            for (int i = 0; i < 3; ++i) {
                if (dl[i] == 0.0) {
                    if (std::abs(o[i]) > c.size[i]) return false;
                    continue;
                }
                double ta = (-c.size[i] - o[i]) / dl[i];
                double tb = (c.size[i] - o[i]) / dl[i];
                if (ta > tb) std::swap(ta, tb);
                if (ta > t0) t0 = ta, a0 = i;
                if (tb < t1) t1 = tb, a1 = i;
            }
            if (t0 > t1) return false;
            double t;
            int axis;
            double outward;  // sign of the hit face's outward normal along its axis
            double facing;   // +1: outward normal faces the origin (hit from outside)
            if (t0 > kTMin) {
                t = t0, axis = a0, outward = dl[a0] > 0.0 ? -1.0 : 1.0, facing = 1.0;
            } else if (t1 > kTMin) {
                t = t1, axis = a1, outward = dl[a1] > 0.0 ? 1.0 : -1.0, facing = -1.0;
            } else {
                return false;
            }
            if (t > t_max) return false;
            hit.t = t;
            hit.face_id = c.first_face + 2 * axis + (outward > 0.0 ? 0 : 1);
            hit.normal = (outward * facing) * c.axes.col(axis);
            return true;
        }
        case Compiled::Kind::kCylinder: {
            const Vec3d a = c.axes.col(0);
            const double r = c.size.x(), len = c.size.y();
            const Vec3d w = ray.origin - c.origin;
            const double da = d.dot(a), wa = w.dot(a);
            const Vec3d dp = d - da * a, wp = w - wa * a;
            double best = t_max;
            bool found = false;
            const double aa = dp.squaredNorm();
            if (aa > 1e-18) {
                const double b = dp.dot(wp);
                const double disc = b * b - aa * (wp.squaredNorm() - r * r);
                if (disc >= 0.0) {
                    const double sq = std::sqrt(disc);
                    for (const double t : {(-b - sq) / aa, (-b + sq) / aa}) {
                        if (!(t > kTMin && t <= best)) continue;
                        const double s = wa + t * da;
                        if (s < 0.0 || s > len) continue;
                        best = t;
                        hit.face_id = c.first_face;
                        hit.normal = (wp + t * dp) / r;
                        found = true;
                        break;
                    }
                }
            }
            if (c.capped && std::abs(da) > 1e-15) {
                for (int k = 0; k < 2; ++k) {
                    const double t = ((k == 0 ? 0.0 : len) - wa) / da;
                    if (!(t > kTMin && t <= best)) continue;
                    if ((wp + t * dp).squaredNorm() > r * r) continue;
                    best = t;
                    hit.face_id = c.first_face + 1 + k;
                    hit.normal = k == 0 ? Vec3d(-a) : a;
                    found = true;
                }
            }
            if (!found) return false;
            hit.t = best;
            if (hit.normal.dot(d) > 0.0) hit.normal = -hit.normal;
            return true;
        }
    }
    return false;
}

bool Scene::intersect(const Ray& ray, double t_max, Hit& hit) const {
    if (nodes_.empty()) return false;
    Vec3d inv;
    for (int i = 0; i < 3; ++i) inv[i] = ray.direction[i] == 0.0 ? 1e300 : 1.0 / ray.direction[i];
    // Stack of (node, entry distance): a node whose entry lies beyond the best hit so far is
    // skipped without testing its box again.
    std::array<std::pair<std::int32_t, double>, 128> stack{};
    std::size_t top = 0;
    double t_root;
    if (!ray_box(nodes_[0].lo, nodes_[0].hi, ray.origin, inv, t_max, t_root)) return false;
    stack[top++] = {0, t_root};
    double best = t_max;
    bool found = false;
    Hit h;
    while (top > 0) {
        const auto [index, t_node] = stack[--top];
        if (t_node > best) continue;
        const Node& node = nodes_[static_cast<std::size_t>(index)];
        if (node.count > 0) {
            for (std::int32_t i = node.first; i < node.first + node.count; ++i) {
                const std::int32_t p = order_[static_cast<std::size_t>(i)];
                if (hit_primitive(compiled_[static_cast<std::size_t>(p)], ray, best, h)) {
                    h.primitive = p;
                    best = h.t;
                    hit = h;
                    found = true;
                }
            }
            continue;
        }
        // Visit the nearer child first (pushed last) so the far one is usually culled.
        const std::int32_t li = node.first, ri = node.first + 1;
        const Node& l = nodes_[static_cast<std::size_t>(li)];
        const Node& r = nodes_[static_cast<std::size_t>(ri)];
        double tl, tr;
        const bool hl = ray_box(l.lo, l.hi, ray.origin, inv, best, tl);
        const bool hr = ray_box(r.lo, r.hi, ray.origin, inv, best, tr);
        if (hl && hr) {
            if (tl <= tr) {
                stack[top++] = {ri, tr};
                stack[top++] = {li, tl};
            } else {
                stack[top++] = {li, tl};
                stack[top++] = {ri, tr};
            }
        } else if (hl) {
            stack[top++] = {li, tl};
        } else if (hr) {
            stack[top++] = {ri, tr};
        }
    }
    return found;
}

std::optional<Hit> Scene::intersect(const Ray& ray, double t_max) const {
    Hit hit;
    if (!intersect(ray, t_max, hit)) return std::nullopt;
    return hit;
}

Vec3d Scene::normal_at(std::int32_t face_id, const Vec3d& p) const {
    if (face_id < 0 || static_cast<std::size_t>(face_id) >= faces_.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"no face with id ", std::to_string(face_id), " in this scene"}));
    return faces_[static_cast<std::size_t>(face_id)].normal_at(p);
}

std::vector<Face> Scene::planar_faces() const {
    std::vector<Face> out;
    for (const Face& f : faces_)
        if (f.planar()) out.push_back(f);
    return out;
}

}  // namespace surfgrow::scanner
