#include "surfgrow/core/detail/strip_growing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "surfgrow/core/detail/neighbourhood_fit.hpp"
#include "surfgrow/core/detail/parallel_errors.hpp"
#include "surfgrow/core/detail/slab_colours.hpp"

namespace surfgrow::detail {

namespace {
// A neighbourhood of this many times min_pts that is still narrow is no strip at any radius.
constexpr double kEnoughPoints = 10.0;

/// The leftovers (a few per mille of the points) bucketed in cells of one side, keyed x, y, z
/// (21 bits each, wrapping), sorted by key and then point.
class LeftoverCells {
  public:
    using Cell = std::array<std::int64_t, 3>;

    LeftoverCells(const CubeIndex& index, std::span<const std::int32_t> labels, double side)
        : side_(side) {
        for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(index.size()); ++i)
            if (labels[i] < 0) {
                const Cell c = cell_of(index.local_point(i));
                left_.push_back({key_of(c[0], c[1], c[2]), i});
            }
        std::sort(left_.begin(), left_.end());
    }

    [[nodiscard]] Cell cell_of(const Vec3f& p) const {
        Cell c;
        for (int a = 0; a < 3; ++a)
            c[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(
                std::clamp(std::floor(static_cast<double>(p[a]) / side_), -4e18, 4e18));
        return c;
    }

    /// Calls f(point) for each leftover in cells (x, y, z0 .. z1), in key order (z may wrap at
    /// 2^21: then two ranges of keys).
    template <class F>
    void each_in(std::int64_t x, std::int64_t y, std::int64_t z0, std::int64_t z1, F&& f) const {
        auto range = [&](std::uint64_t k0, std::uint64_t k1) {
            auto it = std::lower_bound(left_.begin(), left_.end(), Keyed{k0, 0});
            for (; it != left_.end() && it->key <= k1; ++it) f(it->point);
        };
        const std::uint64_t k0 = key_of(x, y, z0), k1 = key_of(x, y, z1);
        if (k0 <= k1) {
            range(k0, k1);
        } else {
            range(k0, key_of(x, y, kMask));
            range(key_of(x, y, 0), k1);
        }
    }

  private:
    static constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
    static std::uint64_t key_of(std::int64_t x, std::int64_t y, std::int64_t z) {
        return (static_cast<std::uint64_t>(x) & kMask) << 42 |
               (static_cast<std::uint64_t>(y) & kMask) << 21 |
               (static_cast<std::uint64_t>(z) & kMask);
    }
    struct Keyed {
        std::uint64_t key;
        std::uint32_t point;
        bool operator<(const Keyed& o) const {
            return key < o.key || (key == o.key && point < o.point);
        }
    };
    double side_;
    std::vector<Keyed> left_;
};
}  // namespace

std::uint64_t grow_strips(const GrowContext& ctx, std::span<const Slab> slabs, int threads,
                          std::vector<Surface>& surfaces, std::vector<std::uint32_t>& home_of,
                          std::vector<double>& tolerance) {
    const CubeIndex& index = ctx.index;
    const GrowerConfig& cfg = ctx.config;
    if (cfg.plane_test != PlaneTest::kDisk || !ctx.noise.known()) return 0;
    const std::span<std::int32_t> labels = ctx.labels;
    const DiskTest disk = cfg.disk_test();
    const StripTest strip;
    // The balls: from mu up to the adaptive radius in steps of sqrt(2) (a strip's ball must hold
    // enough of it to fix its normal, yet not so much of its length that it reads as a line).
    const double max_radius = cfg.max_radius();
    std::vector<double> radii;
    std::vector<float> radii2;
    for (double radius = cfg.mu; radius <= max_radius * (1 + 1e-9); radius *= std::numbers::sqrt2) {
        radii.push_back(radius);
        radii2.push_back(static_cast<float>(radius * radius));
    }
    // The leftovers bucketed in cells 2 mu wide: a home gathers them ring of cells by ring as its
    // balls grow, so a search that ends at its first balls (most do) visits only the leftovers
    // near it.
    const double cell = 2 * cfg.mu;
    const LeftoverCells left(index, labels, cell);
    // The smallest ball that holds a point at squared distance d2; radii.size(): none (beyond the
    // largest ball it counts for nothing).
    auto ball_of = [&](float d2) {
        std::size_t b = 0;
        while (b < radii2.size() && d2 > radii2[b]) ++b;
        return b;
    };
    // Rings of cells a ball of each size needs (a point within r lies within ceil(r / cell) rings;
    // cells of mu made the channel's sparse leftovers look up too many empty ones).
    std::vector<std::int64_t> ring_of(radii.size());
    for (std::size_t b = 0; b < radii.size(); ++b)
        ring_of[b] = static_cast<std::int64_t>(std::ceil(radii[b] / cell - 1e-9));
    // What one slab grows: its strips in home order, and each member point with its strip's
    // number in that list. Its members hold kTaken meanwhile: taken, so later homes skip them.
    struct SlabStrips {
        std::vector<Surface> surfaces;
        std::vector<std::uint32_t> home_of;
        std::vector<std::pair<std::uint32_t, std::uint32_t>> members;  // (point, strip)
    };
    constexpr std::int32_t kTaken = std::numeric_limits<std::int32_t>::max();
    std::vector<SlabStrips> grown_in(slabs.size());
    // Per thread: per ball, its new points; the members gathered so far.
    struct StripScratch {
        std::vector<std::vector<std::uint32_t>> in_ball;
        std::vector<std::uint32_t> members;
    };
    std::vector<StripScratch> scratch(static_cast<std::size_t>(std::max(threads, 1)));
    for (StripScratch& sc : scratch) sc.in_ball.resize(radii.size());
    // A home whose balls hold no strip leaves its mu-neighbours untried as homes: their balls
    // are nearly its own (without this, a cluttered room's leftovers cost seconds). Bytes, not
    // bits: slabs of one colour mark their own points at once.
    std::vector<std::uint8_t> tried(index.size(), 0);
    auto grow_slab_strips = [&](const Slab& slab, StripScratch& sc, SlabStrips& out) {
        auto& in_ball = sc.in_ball;
        auto& members = sc.members;
        const auto first = static_cast<std::uint32_t>(index.cube_begin(slab.cube_begin));
        const auto last = static_cast<std::uint32_t>(index.cube_begin(slab.cube_end));
        // Homes in index order: every point still unregistered (a leftover no strip took yet).
        for (std::uint32_t home = first; home < last; ++home) {
            if (labels[home] >= 0 || tried[home])
                continue;  // registered, or near a home that failed
            const Vec3f h = index.local_point(home);
            const LeftoverCells::Cell c = left.cell_of(h);
            for (auto& list : in_ball) list.clear();
            // The leftovers in cells (x, y, z0 .. z1) into the balls that hold them.
            auto gather = [&](std::int64_t x, std::int64_t y, std::int64_t z0, std::int64_t z1) {
                left.each_in(x, y, z0, z1, [&](std::uint32_t q) {
                    // The distance first: a point beyond the largest ball is not this home's to
                    // read.
                    const std::size_t ball = ball_of((index.local_point(q) - h).squaredNorm());
                    if (ball < radii.size() && labels[q] < 0) in_ball[ball].push_back(q);
                });
            };
            std::int64_t gathered = -1;  // rings gathered so far
            // Ring R of cells around c: the columns new at R whole, the inner columns' two new
            // ends.
            auto gather_ring = [&](std::int64_t r) {
                if (r == 0) {
                    gather(c[0], c[1], c[2], c[2]);
                    return;
                }
                for (std::int64_t dx = -r; dx <= r; ++dx)
                    for (std::int64_t dy = -r; dy <= r; ++dy) {
                        if (std::max(std::abs(dx), std::abs(dy)) == r) {
                            gather(c[0] + dx, c[1] + dy, c[2] - r, c[2] + r);
                        } else {
                            gather(c[0] + dx, c[1] + dy, c[2] - r, c[2] - r);
                            gather(c[0] + dx, c[1] + dy, c[2] + r, c[2] + r);
                        }
                    }
            };
            bool made = false;
            const Vec3d towards = ctx.sight.towards(home, h);
            const double range = ctx.sight.origins.empty() ? 0.0 : towards.norm();
            const Vec3d sight = ctx.sight.named ? towards : Vec3d::Zero();
            const double sigma = ctx.noise.sigma(range);
            const double max_var = cfg.thickness_sigmas * cfg.thickness_sigmas * sigma * sigma;
            Moments m;
            members.clear();
            for (std::size_t ball = 0; ball < radii.size(); ++ball) {
                const double radius = radii[ball];
                while (gathered < ring_of[ball]) gather_ring(++gathered);
                for (const std::uint32_t q : in_ball[ball]) {
                    m.add((index.local_point(q) - h).cast<double>());
                    members.push_back(q);
                }
                if (m.n < cfg.min_pts) continue;  // too few yet: a larger ball
                const PlaneFit fit = fit_plane(m);
                const PlaneVerdict verdict = judge_strip(disk, strip, fit.eigenvalues, m.n,
                                                         fit.normal, radius, sigma, max_var, sight);
                // A larger ball may hold more of a strip; not of one that is narrow with this many
                // points already (a line or a blob only lengthens).
                if (verdict == PlaneVerdict::kNarrow && m.n < kEnoughPoints * cfg.min_pts) continue;
                if (verdict != PlaneVerdict::kPlane) break;  // thick or edge-on: no strip here
                Neighbourhood nb;
                nb.radius = radius;
                nb.range = ctx.sight.origins.empty() ? -1.0 : range;
                nb.fit = fit;
                const double tol = tolerance_of(ctx, nb);
                const Vec3f normal = fit.normal.cast<float>();
                const Vec3f centre = h + fit.centroid.cast<float>();
                const auto sid = static_cast<std::uint32_t>(out.surfaces.size());
                // Its members: the leftovers within its tolerance of its plane. (Taking points from
                // other surfaces where they fit the strip better was tried: it raised the channel's
                // p95 from 1.4 to 2.2 degrees, the strips' planes leaning into the faces beside
                // them.)
                for (const std::uint32_t j : members)
                    if (static_cast<double>(std::abs(normal.dot(index.local_point(j) - centre))) <=
                        tol) {
                        labels[j] = kTaken;
                        out.members.emplace_back(j, sid);
                    }
                Surface& s = out.surfaces.emplace_back();
                s.home = index.world_point(home);
                s.centroid = s.home + fit.centroid;
                s.normal = fit.normal;
                s.eigenvalues = fit.eigenvalues;
                s.radius = radius;
                s.neighbours = static_cast<std::uint32_t>(m.n);
                s.tolerance = tol;
                out.home_of.push_back(home);
                made = true;
                break;
            }
            if (made) continue;
            for (const std::uint32_t q : in_ball[0]) tried[q] = true;
        }
    };
    // Slab by slab, even ones then odd ones as in growing: a home's balls reach at most one slab
    // either side, so the slabs of one colour read and write disjoint points. The strips are
    // numbered in slab order, even slabs first: the same result for any thread count.
    ParallelErrors errors;
    for (int colour = 0; colour < 2; ++colour)
        for_each_slab_of_colour(index, slabs, colour, threads, [&](std::size_t s, int t) {
            errors.run(s, [&] {
                grow_slab_strips(slabs[s], scratch[static_cast<std::size_t>(t)], grown_in[s]);
            });
        });
    errors.rethrow();
    std::uint64_t grown = 0;
    for (int colour = 0; colour < 2; ++colour)
        for (std::size_t s = static_cast<std::size_t>(colour); s < slabs.size(); s += 2) {
            SlabStrips& g = grown_in[s];
            const auto base = static_cast<std::int32_t>(surfaces.size());
            for (const auto& [point, number] : g.members)
                labels[point] = base + static_cast<std::int32_t>(number);
            surfaces.insert(surfaces.end(), g.surfaces.begin(), g.surfaces.end());
            home_of.insert(home_of.end(), g.home_of.begin(), g.home_of.end());
            for (const Surface& strip_surface : g.surfaces)
                tolerance.push_back(strip_surface.tolerance);
            grown += g.surfaces.size();
        }
    return grown;
}

namespace {

// Round by round, each leftover within reach of a point taken in the round before (the first
// round: of `frontier`) and within its tolerance of that point's surface's plane joins the
// surface it fits best (ties by number). Only surfaces `first` on take points. With `refit`,
// each surface's plane is refitted to all its members round by round, a surface that reached
// farther keeps it, and its members beyond its tolerance of it are left out; without, every
// surface keeps its plane. Returns the members gained (less those left out).
std::int64_t extend_along_faces(const GrowContext& ctx, std::int32_t first,
                                std::vector<Surface>& surfaces, std::span<const double> tolerance,
                                std::vector<std::uint32_t> frontier, bool refit) {
    if (frontier.empty()) return 0;  // no round would take a point, and none reached farther
    const CubeIndex& index = ctx.index;
    const std::span<std::int32_t> labels = ctx.labels;
    // A surface reaches from each member as far as the leftover pass reaches beside surfaces, or
    // as its own ball where that is wider: its ball grew to hold enough points, so beyond the
    // sensor's spacing there (a far edge seen at grazing incidence: 25-30 mm between lines).
    const double cell = kMissRadiusPerMu * ctx.config.mu;
    const LeftoverCells left(index, labels, cell);
    // With `refit`, each surface's plane refitted to all its members, round by round: along a
    // long strip its normal, fitted to the first ball, leans by a few degrees, which a few ball
    // lengths farther puts the face outside the tolerance.
    const auto count = refit ? surfaces.size() - static_cast<std::size_t>(first) : 0;
    std::vector<Moments> moments(count);
    std::vector<Vec3d> normal(count), centre(count);
    std::vector<std::uint8_t> grew(count, 0), extended(count, 0);
    auto add = [&](std::uint32_t i) {
        if (!refit) return;
        const auto k = static_cast<std::size_t>(labels[i] - first);
        moments[k].add(index.world_point(i) - surfaces[k + static_cast<std::size_t>(first)].home);
        grew[k] = 1;
    };
    auto refit_grown = [&] {
        for (std::size_t k = 0; k < count; ++k)
            if (grew[k]) {
                const PlaneFit fit = fit_plane(moments[k]);
                normal[k] = fit.normal;
                centre[k] = surfaces[k + static_cast<std::size_t>(first)].home + fit.centroid;
                grew[k] = 0;
            }
    };
    auto plane_of = [&](std::int32_t sid) -> std::pair<const Vec3d&, const Vec3d&> {
        if (!refit)
            return {surfaces[static_cast<std::size_t>(sid)].normal,
                    surfaces[static_cast<std::size_t>(sid)].centroid};
        const auto k = static_cast<std::size_t>(sid - first);
        return {normal[k], centre[k]};
    };
    if (refit)
        for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(index.size()); ++i)
            if (labels[i] >= first) add(i);
    struct Offer {
        std::uint32_t point;
        double distance;
        std::int32_t surface;
        bool operator<(const Offer& o) const {
            if (point != o.point) return point < o.point;
            return distance < o.distance || (distance == o.distance && surface < o.surface);
        }
    };
    std::vector<Offer> offers;
    std::int64_t gained = 0;
    while (!frontier.empty()) {
        refit_grown();
        offers.clear();
        // The frontier is in index order, so neighbours share a cell: the leftovers around a
        // surface's cell, still offered to none of its points, are gathered once for them all.
        std::vector<std::uint32_t> near;
        std::int32_t near_surface = -1;
        LeftoverCells::Cell near_cell{};
        for (const std::uint32_t f : frontier) {
            const std::int32_t sid = labels[f];
            const double step = std::max(cell, surfaces[static_cast<std::size_t>(sid)].radius);
            const Vec3f p = index.local_point(f);
            const LeftoverCells::Cell c = left.cell_of(p);
            if (sid != near_surface || c != near_cell) {
                near_surface = sid;
                near_cell = c;
                near.clear();
                const auto rings = static_cast<std::int64_t>(std::ceil(step / cell - 1e-9));
                for (std::int64_t dx = -rings; dx <= rings; ++dx)
                    for (std::int64_t dy = -rings; dy <= rings; ++dy)
                        left.each_in(c[0] + dx, c[1] + dy, c[2] - rings, c[2] + rings,
                                     [&](std::uint32_t q) {
                                         if (labels[q] < 0) near.push_back(q);
                                     });
            }
            const double tol = tolerance[static_cast<std::size_t>(sid)];
            const auto [n, o] = plane_of(sid);
            const auto step2 = static_cast<float>(step * step);
            for (std::size_t j = 0; j < near.size();) {
                const std::uint32_t q = near[j];
                if ((index.local_point(q) - p).squaredNorm() > step2) {
                    ++j;
                    continue;
                }
                const double d = std::abs(n.dot(index.world_point(q) - o));
                if (d <= tol) offers.push_back({q, d, sid});
                near[j] = near.back();  // judged for this surface: no other of its points asks
                near.pop_back();
            }
        }
        // Each point to the surface it fits best (ties by number), all at once: the same for any
        // order of the frontier.
        std::sort(offers.begin(), offers.end());
        frontier.clear();
        for (std::size_t k = 0; k < offers.size(); ++k)
            if (k == 0 || offers[k].point != offers[k - 1].point) {
                labels[offers[k].point] = offers[k].surface;
                frontier.push_back(offers[k].point);
                add(offers[k].point);
                if (refit) extended[static_cast<std::size_t>(offers[k].surface - first)] = 1;
            }
        gained += static_cast<std::int64_t>(frontier.size());
    }
    if (!refit) return gained;
    // A surface that reached farther takes the plane of all its members (as pooling refines a
    // disk's normal), and keeps those within its tolerance of it: every member of a surface lies
    // within its tolerance of its plane.
    for (std::size_t k = 0; k < count; ++k)
        if (extended[k]) {
            Surface& strip = surfaces[k + static_cast<std::size_t>(first)];
            strip.normal = normal[k];
            strip.centroid = centre[k];
        }
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(index.size()); ++i) {
        if (labels[i] < first || !extended[static_cast<std::size_t>(labels[i] - first)]) continue;
        const auto sid = static_cast<std::size_t>(labels[i]);
        const Surface& strip = surfaces[sid];
        if (std::abs(strip.normal.dot(index.world_point(i) - strip.centroid)) > tolerance[sid]) {
            labels[i] = -1;
            --gained;  // a member before, or taken by a round
        }
    }
    return gained;
}

}  // namespace

std::int64_t extend_strips(const GrowContext& ctx, std::int32_t first_strip,
                           std::vector<Surface>& surfaces, std::span<const double> tolerance) {
    std::vector<std::uint32_t> frontier;
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(ctx.index.size()); ++i)
        if (ctx.labels[i] >= first_strip) frontier.push_back(i);
    return extend_along_faces(ctx, first_strip, surfaces, tolerance, std::move(frontier), true);
}

std::int64_t extend_surfaces(const GrowContext& ctx, std::vector<Surface>& surfaces,
                             std::span<const double> tolerance,
                             std::vector<std::uint32_t> frontier) {
    return extend_along_faces(ctx, 0, surfaces, tolerance, std::move(frontier), false);
}

}  // namespace surfgrow::detail
