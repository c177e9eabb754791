#include "surfgrow/core/detail/strip_growing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "surfgrow/core/detail/neighbourhood_fit.hpp"

namespace surfgrow::detail {

namespace {
// A neighbourhood of this many times min_pts that is still narrow is no strip at any radius.
constexpr double kEnoughPoints = 10.0;
}  // namespace

std::uint64_t grow_strips(const GrowContext& ctx, std::vector<Surface>& surfaces,
                          std::vector<std::uint32_t>& home_of, std::vector<double>& tolerance) {
    const CubeIndex& index = ctx.index;
    const GrowerConfig& cfg = ctx.config;
    if (cfg.plane_test != PlaneTest::kDisk || !ctx.noise.known()) return 0;
    const std::span<std::int32_t> labels = ctx.labels;
    const DiskTest disk = cfg.disk_test();
    const StripTest strip;
    // The leftovers (a few per mille of the points) bucketed in cells as wide as the adaptive
    // radius, so that a neighbourhood visits the 27 cells around its home and leftovers only. Cell
    // coordinates wrap at 2^21: far cells that share a key only add candidates the distance test
    // drops.
    const double max_radius = cfg.max_radius();
    const double cell = max_radius;
    // Cell coordinates as int64, clamped: any extent and any mu stay defined.
    using Cell = std::array<std::int64_t, 3>;
    auto cell_of = [&](const Vec3f& p) {
        Cell c;
        for (int a = 0; a < 3; ++a)
            c[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(
                std::clamp(std::floor(static_cast<double>(p[a]) / cell), -4e18, 4e18));
        return c;
    };
    auto key_of = [](const Cell& c, int dx, int dy, int dz) {
        constexpr std::uint64_t mask = (std::uint64_t{1} << 21) - 1;
        return (static_cast<std::uint64_t>(c[0] + dx) & mask) << 42 |
               (static_cast<std::uint64_t>(c[1] + dy) & mask) << 21 |
               (static_cast<std::uint64_t>(c[2] + dz) & mask);
    };
    struct Keyed {
        std::uint64_t key;
        std::uint32_t point;
        bool operator<(const Keyed& o) const {
            return key < o.key || (key == o.key && point < o.point);
        }
    };
    std::vector<Keyed> left;
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(index.size()); ++i)
        if (labels[i] < 0) left.push_back({key_of(cell_of(index.local_point(i)), 0, 0, 0), i});
    std::sort(left.begin(), left.end());
    // The balls: from mu up to the adaptive radius in steps of sqrt(2) (a strip's ball must hold
    // enough of it to fix its normal, yet not so much of its length that it reads as a line).
    std::vector<double> radii;
    std::vector<float> radii2;
    for (double radius = cfg.mu; radius <= max_radius * (1 + 1e-9); radius *= std::numbers::sqrt2) {
        radii.push_back(radius);
        radii2.push_back(static_cast<float>(radius * radius));
    }
    // The smallest ball that holds a point at squared distance d2; radii.size(): none (beyond the
    // largest ball it counts for nothing).
    auto ball_of = [&](float d2) {
        std::size_t b = 0;
        while (b < radii2.size() && d2 > radii2[b]) ++b;
        return b;
    };
    struct Near {
        std::uint32_t point;
        std::uint32_t ball;
    };
    std::vector<Near> near, by_ball;
    std::vector<std::uint32_t> first(radii.size() + 1);
    std::uint64_t grown = 0;
    // A home whose balls hold no strip leaves its mu-neighbours untried as homes: their balls
    // are nearly its own (without this, a cluttered room's leftovers cost seconds).
    std::vector<bool> tried(index.size(), false);
    // Homes in index order: every point still unregistered (a leftover no strip took yet).
    for (std::uint32_t home = 0; home < static_cast<std::uint32_t>(index.size()); ++home) {
        if (labels[home] >= 0 || tried[home]) continue;  // registered, or near a home that failed
        const Vec3f h = index.local_point(home);
        // Every leftover within the adaptive radius, nearest first.
        near.clear();
        const Cell c = cell_of(h);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::uint64_t key = key_of(c, dx, dy, dz);
                    auto it = std::lower_bound(left.begin(), left.end(), Keyed{key, 0});
                    for (; it != left.end() && it->key == key; ++it) {
                        if (labels[it->point] >= 0) continue;
                        const std::size_t ball =
                            ball_of((index.local_point(it->point) - h).squaredNorm());
                        if (ball < radii.size())
                            near.push_back({it->point, static_cast<std::uint32_t>(ball)});
                    }
                }
        if (near.size() < static_cast<std::size_t>(cfg.min_pts)) continue;
        bool made = false;
        // Nearest ball first (a counting sort on the smallest ball that holds each point; the
        // gathering's order within a ball): what each larger ball adds follows what it held.
        std::fill(first.begin(), first.end(), 0);
        for (const Near& q : near) ++first[q.ball + 1];
        for (std::size_t b = 1; b < first.size(); ++b) first[b] += first[b - 1];
        by_ball.resize(near.size());
        for (const Near& q : near) by_ball[first[q.ball]++] = q;
        near.swap(by_ball);
        const Vec3d towards = ctx.sight.towards(home, h);
        const double range = ctx.sight.origins.empty() ? 0.0 : towards.norm();
        const Vec3d sight = ctx.sight.named ? towards : Vec3d::Zero();
        const double sigma = ctx.noise.sigma(range);
        const double max_var = cfg.thickness_sigmas * cfg.thickness_sigmas * sigma * sigma;
        Moments m;
        std::size_t inside = 0;
        for (std::size_t ball = 0; ball < radii.size(); ++ball) {
            const double radius = radii[ball];
            for (; inside < near.size() && near[inside].ball <= ball; ++inside)
                m.add((index.local_point(near[inside].point) - h).cast<double>());
            if (m.n < cfg.min_pts) continue;  // too few yet: a larger ball
            const PlaneFit fit = fit_plane(m);
            const PlaneVerdict verdict = judge_strip(disk, strip, fit.eigenvalues, m.n, fit.normal,
                                                     radius, sigma, max_var, sight);
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
            const auto sid = static_cast<std::int32_t>(surfaces.size());
            // Its members: the leftovers within its tolerance of its plane. (Taking points from
            // other surfaces where they fit the strip better was tried: it raised the channel's
            // p95 from 1.4 to 2.2 degrees, the strips' planes leaning into the faces beside them.)
            for (std::size_t k = 0; k < inside; ++k) {
                const std::uint32_t j = near[k].point;
                if (static_cast<double>(std::abs(normal.dot(index.local_point(j) - centre))) <= tol)
                    labels[j] = sid;
            }
            Surface& s = surfaces.emplace_back();
            s.home = index.world_point(home);
            s.centroid = s.home + fit.centroid;
            s.normal = fit.normal;
            s.eigenvalues = fit.eigenvalues;
            s.radius = radius;
            s.neighbours = static_cast<std::uint32_t>(m.n);
            s.tolerance = tol;
            home_of.push_back(home);
            tolerance.push_back(tol);
            ++grown;
            made = true;
            break;
        }
        if (made) continue;
        for (const Near& q : near) {
            if (q.ball > 0) break;  // the first ball's come first
            tried[q.point] = true;
        }
    }
    return grown;
}

}  // namespace surfgrow::detail
