#include "surfgrow/core/detail/leftover_pass.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "surfgrow/core/detail/cube_surfaces.hpp"
#include "surfgrow/core/detail/parallel_errors.hpp"
#include "surfgrow/core/plane_fit.hpp"
#include "surfgrow/core/plane_test.hpp"

namespace surfgrow::detail {

namespace {

// Fused clouds: a leftover that lies in another scan's layer of a surface, as far from it as this
// many sigmas of the measured layer offsets, goes to that surface (attach_layer). Each face has
// one offset per scan, and the budget must hold the largest of a cloud's tens to hundreds of
// them: beyond 3 sigmas lies one in 370, beyond 4 one in 16,000. At 3 the 3-pose channel's flange
// underside, 3.9 sigmas off in one scan (pose seed 5), stayed out (its 1.5-2 m band 97.8 %); at 5
// wrong layers join (more bound-plane points > 45 degrees off). docs/algorithm.md.
constexpr double kLayerSigmas = 4.0;
// ... if at least this many unregistered points of its own scan around it make that layer,
constexpr int kLayerMinPoints = 4;
// ... and a layer whose own plane the noise leaves fixed within kLayerNormalError (the standard
// error of its normal about its narrow axis, as the strip test's) lies within 45 degrees of the
// surface's plane (kLayerMaxTiltCos): the wrong case is a narrow face's band across the plane, 90
// degrees off; a pipe's layer beside a patch of it leans by the curvature between them.
constexpr double kLayerMaxTiltCos = 0.7071067811865476;  // cos 45 degrees
constexpr double kLayerNormalError = 0.176;              // tan 10 degrees
// The wider searches double their radius at most this many times (the adaptive radius's 64 mu).
constexpr std::size_t kFarLevels = 7;

/// A surface near a leftover, and the leftover's signed distance to its plane.
struct Candidate {
    std::int32_t surface;
    double distance;
};

/// Fused clouds: the surface whose plane, shifted to this point's scan's layer, the point fits
/// best; -1 if none; `ray` runs from its sensor to the point. A scan sees a surface a little off
/// the others (its range bias, its pose error), so where growing found only the other scans' layer,
/// this scan's points lie beside it, farther than the noise within a layer. `layer` holds the
/// unregistered points of the point's own scan around it: it must be as thin as the noise, parallel
/// to the surface (its distances to the plane agree; where it spans two dimensions, its own plane
/// within 45 degrees: a narrow face's leftovers beside the next face are a thin band across
/// its plane, not a layer of it), and offset from it by at most kLayerSigmas of the measured layer
/// offsets; the point must lie within the surface's tolerance of the layer's median.
std::int32_t attach_layer(const GrowContext& ctx, const Vec3d& ray,
                          std::span<const Candidate> candidates,
                          const std::vector<Surface>& surfaces, std::span<const double> tolerance,
                          std::vector<Vec3f>& layer, std::vector<double>& dist) {
    if (layer.size() < static_cast<std::size_t>(kLayerMinPoints)) return -1;
    const CubeIndex& index = ctx.index;
    const double range = ray.norm();
    if (!(range > 0)) return -1;  // a point on its sensor has no ray
    const double noise = ctx.noise.sigma(range);
    const double max_spread = ctx.config.thickness_sigmas * noise;
    // The layer's own plane, where it has one: not a line (the strip test's rule), and its
    // normal's standard error sigma / sqrt(n lambda_mid) within kLayerNormalError.
    Moments about_first;
    for (const Vec3f& q : layer) about_first.add((q - layer[0]).cast<double>());
    const PlaneFit own = fit_plane(about_first);
    const Vec3d& e = own.eigenvalues;
    const bool has_plane =
        e[1] > 0 && e[1] >= StripTest{}.min_line_ratio * e[2] &&
        noise * noise <= kLayerNormalError * kLayerNormalError * about_first.n * e[1];
    std::int32_t best = -1;
    double best_fit = 0;
    for (const Candidate& cand : candidates) {
        const auto sid = static_cast<std::size_t>(cand.surface);
        const Surface& surf = surfaces[sid];
        const Vec3f n = surf.normal.cast<float>();
        if (has_plane && std::abs(surf.normal.dot(own.normal)) < kLayerMaxTiltCos) continue;
        const Vec3f c = index.to_local(surf.centroid);
        const double max_offset = kLayerSigmas * ctx.layers.sigma(range) *
                                  std::max(std::abs(surf.normal.dot(ray)) / range, kMinLayerCos);
        dist.clear();
        for (const Vec3f& q : layer) dist.push_back(static_cast<double>(n.dot(q - c)));
        const auto mid = dist.begin() + static_cast<std::ptrdiff_t>(dist.size() / 2);
        std::nth_element(dist.begin(), mid, dist.end());
        const double m = *mid;
        if (std::abs(m) > max_offset) continue;
        double sq = 0;
        for (const double d : dist) sq += (d - m) * (d - m);
        if (sq > max_spread * max_spread * double(dist.size())) continue;
        const double fit = std::abs(cand.distance - m);
        if (fit <= tolerance[sid] && (best < 0 || fit < best_fit)) {
            best = cand.surface;
            best_fit = fit;
        }
    }
    return best;
}

/// A cube within a search's reach and the low corner of its box (local frame).
struct NearCube {
    std::uint32_t cube;
    Vec3f low;
};

/// A thread's buffers for the leftover pass (a cache line of its own, as Scratch).
struct alignas(64) LeftoverScratch {
    std::vector<Range> runs;                                   // of cubes
    std::array<std::vector<NearCube>, kFarLevels + 1> levels;  // [0]: within mu; then far levels
    // Per level, the surfaces in its cubes (once per cube, for all its leftovers) and whether
    // they are listed yet.
    std::array<std::vector<std::int32_t>, kFarLevels + 1> level_surfaces;
    std::array<bool, kFarLevels + 1> listed{};
    std::vector<const NearCube*> reach;  // the cubes a ball may touch
    std::vector<std::uint32_t> seen;     // per surface: last listing's stamp
    std::uint32_t stamp = 0;
    std::vector<std::pair<double, std::int32_t>> fitting;
    std::vector<Candidate> candidates;
    std::vector<double> dist;
    std::vector<Vec3f> layer;
};

/// Leftover pass: for each unregistered point, the neighbouring surface whose plane it fits best.
/// Reads only labels fixed by growing and writes to `attach`, so slabs can run in any order.
/// A surface is a neighbour at radius r if one of its points lies within r: the best-fitting of
/// those is the same as a visit of every point within r would find (ties by surface id). The
/// surfaces around a cube are listed once for all its leftovers; each leftover's box test runs
/// only on the cubes that hold a surface it fits (and, for counting, on those it must scan).
void attach_slab(const GrowContext& ctx, const Slab& slab, const std::vector<Surface>& surfaces,
                 std::span<const double> tolerance, const CubeSurfaces& near_surfaces,
                 LeftoverScratch& s, std::vector<std::pair<std::uint32_t, std::int32_t>>& attach) {
    const CubeIndex& index = ctx.index;
    const GrowerConfig& cfg = ctx.config;
    const std::span<const std::int32_t> labels = ctx.labels;
    const float* xs = index.xs();
    const float* ys = index.ys();
    const float* zs = index.zs();
    const auto cube = static_cast<float>(index.cube_size());
    const bool every_miss = cfg.plane_test == PlaneTest::kDisk;
    // Wider searches double the radius from 2 mu: an isolated point up to the adaptive radius's
    // reach, one beside surfaces that it does not fit up to kMissRadiusPerMu (the surfaces across
    // a band of rejected edge homes). Each stops at the first radius that finds a surface.
    std::vector<double> radii;
    for (double r = 2 * cfg.mu; radii.size() < kFarLevels; r *= 2) {
        radii.push_back(std::min(r, cfg.max_radius()));
        if (r >= cfg.max_radius()) break;
    }
    if (cfg.max_radius() <= cfg.mu) radii.clear();
    const double miss_limit = std::min(cfg.max_radius(), kMissRadiusPerMu * cfg.mu);
    const bool layered = every_miss && ctx.sight.fused() && ctx.layers.known() && !radii.empty();
    if (s.seen.size() != surfaces.size()) s.seen.assign(surfaces.size(), 0);
    for (std::uint32_t c = slab.cube_begin; c < slab.cube_end; ++c) {
        std::uint32_t i = index.cube_begin(c);
        while (i < index.cube_end(c) && labels[i] >= 0) ++i;
        if (i == index.cube_end(c)) continue;  // no leftover here
        for (auto& level : s.levels) level.clear();
        s.listed.fill(false);
        // The cubes of search level `level` around cube c (0: within mu), looked up on first use.
        auto level_cubes = [&](std::size_t level) -> std::span<const NearCube> {
            std::vector<NearCube>& out = s.levels[level];
            if (!out.empty()) return out;
            const int reach =
                level == 0 ? 1 : static_cast<int>(std::ceil(radii[level - 1] / index.cube_size()));
            s.runs.clear();
            index.column_cube_ranges(index.cube_coords(c), reach, s.runs);
            for (const Range& run : s.runs)
                for (std::uint32_t k = run.begin; k < run.end; ++k)
                    out.push_back({k, (index.grid_coords(k) * index.cube_size()).cast<float>()});
            return out;
        };
        // The surfaces of the cubes of a level, in the order first met (the search sorts them).
        auto level_surfaces = [&](std::size_t level) -> const std::vector<std::int32_t>& {
            std::vector<std::int32_t>& out = s.level_surfaces[level];
            if (s.listed[level]) return out;
            s.listed[level] = true;
            out.clear();
            if (++s.stamp == 0) {  // wrapped: forget every earlier stamp
                std::fill(s.seen.begin(), s.seen.end(), 0);
                s.stamp = 1;
            }
            for (const NearCube& nc : level_cubes(level))
                for (const std::int32_t sid : near_surfaces.of(nc.cube)) {
                    std::uint32_t& mark = s.seen[static_cast<std::size_t>(sid)];
                    if (mark == s.stamp) continue;
                    mark = s.stamp;
                    out.push_back(sid);
                }
            return out;
        };
        for (; i < index.cube_end(c); ++i) {
            if (labels[i] >= 0) continue;
            const Vec3f p = index.local_point(i);
            const Vec3d pw = index.origin() + p.cast<double>();
            // Whether point j lies within squared distance r2 of p (float, as the SIMD kernels).
            auto near_p = [&](std::uint32_t j, float r2) {
                const float dx = xs[j] - p.x(), dy = ys[j] - p.y(), dz = zs[j] - p.z();
                return dx * dx + dy * dy + dz * dz <= r2;
            };
            // A cube whose box lies farther than the radius holds no point within it. The margin
            // covers the rounding of float coordinates and box corners: it only keeps a cube in.
            const float margin =
                0.01f * cube + 1e-6f * (std::abs(p.x()) + std::abs(p.y()) + std::abs(p.z()));
            // A cube whose box lies within `reach` of p (the box test).
            auto touches = [&](const NearCube& nc, float reach) {
                float d2 = 0;
                for (int a = 0; a < 3; ++a) {
                    const float lo = nc.low[a] - p[a], hi = p[a] - (nc.low[a] + cube);
                    const float d = std::max({lo, hi, 0.f});
                    d2 += d * d;
                }
                return d2 <= reach * reach;
            };
            // The search at `radius` over the cubes of `level`: the surfaces listed there (some
            // may lie beyond the radius: `within` finds no member of those) and, on demand, the
            // cubes that the ball may touch.
            std::size_t at_level = 0;
            float at_reach = 0;
            bool reach_known = false;
            auto gather = [&](std::size_t level, double radius) {
                at_level = level;
                at_reach = static_cast<float>(radius) + margin;
                reach_known = false;
            };
            auto reach_cubes = [&]() -> const std::vector<const NearCube*>& {
                if (reach_known) return s.reach;
                reach_known = true;
                s.reach.clear();
                for (const NearCube& nc : level_cubes(at_level))
                    if (touches(nc, at_reach)) s.reach.push_back(&nc);
                return s.reach;
            };
            // Whether surface sid has a point within the radius of the last gather().
            auto within = [&](std::int32_t sid, float r2) {
                for (const NearCube& nc : level_cubes(at_level)) {
                    if (!near_surfaces.holds(nc.cube, sid) || !touches(nc, at_reach)) continue;
                    for (std::uint32_t j = index.cube_begin(nc.cube); j < index.cube_end(nc.cube);
                         ++j) {
                        if (labels[j] == sid && near_p(j, r2)) return true;
                    }
                }
                return false;
            };
            // The best-fitting surface within `radius` among the cubes gathered; -1 if none.
            auto best_within = [&](double radius) {
                s.fitting.clear();
                for (const std::int32_t sid : level_surfaces(at_level)) {
                    const auto k = static_cast<std::size_t>(sid);
                    const double d = std::abs(surfaces[k].normal.dot(pw - surfaces[k].centroid));
                    if (d <= tolerance[k]) s.fitting.emplace_back(d, sid);
                }
                std::sort(s.fitting.begin(), s.fitting.end());
                const auto r2 = static_cast<float>(radius * radius);
                for (const auto& [d, sid] : s.fitting)
                    if (within(sid, r2)) return sid;
                return std::int32_t{-1};
            };
            const auto mu2 = static_cast<float>(cfg.mu * cfg.mu);
            gather(0, cfg.mu);
            std::int32_t best = best_within(cfg.mu);
            double last_radius = cfg.mu;
            // Sparse at mu: as far as the adaptive radius reaches. Dense but fitting nothing here
            // (mixed pixels, a rejected edge): only a little farther. Counting stops as soon as
            // the answer is known: min_pts points (the disk test's "dense"), or a registered one.
            bool far = best < 0;
            bool sparse = false;
            if (best < 0) {
                int near = 0;  // points within mu, registered or not
                bool any_neighbour = false;
                auto known = [&] { return every_miss ? near >= cfg.min_pts : any_neighbour; };
                const std::vector<const NearCube*>& reach = reach_cubes();
                for (std::size_t k = 0; k < reach.size() && !known(); ++k)
                    for (std::uint32_t j = index.cube_begin(reach[k]->cube);
                         j < index.cube_end(reach[k]->cube) && !known(); ++j)
                        if (near_p(j, mu2)) {
                            ++near;
                            any_neighbour = any_neighbour || labels[j] >= 0;
                        }
                sparse = !any_neighbour && near < cfg.min_pts;
                far = !any_neighbour || every_miss;
            }
            if (far) {
                const double limit = sparse || !every_miss ? cfg.max_radius() : miss_limit;
                for (std::size_t level = 0; level < radii.size() && best < 0; ++level) {
                    const double radius = std::min(radii[level], limit);
                    gather(level + 1, radius);
                    best = best_within(radius);
                    last_radius = radius;
                    if (radii[level] >= limit) break;
                }
            }
            if (best < 0 && layered) {
                // Fused clouds: the surfaces of the widest search whose plane another layer of
                // this point may be off by (at normal incidence; attach_layer applies each one's).
                const Vec3d ray = ctx.sight.towards(i, p);
                const double layer_reach = kLayerSigmas * ctx.layers.sigma(ray.norm());
                const auto r2 = static_cast<float>(last_radius * last_radius);
                s.candidates.clear();
                for (const std::int32_t sid : level_surfaces(at_level)) {
                    const auto k = static_cast<std::size_t>(sid);
                    const double signed_d = surfaces[k].normal.dot(pw - surfaces[k].centroid);
                    if (tolerance[k] >= 0 && std::abs(signed_d) <= tolerance[k] + layer_reach &&
                        within(sid, r2))
                        s.candidates.push_back({sid, signed_d});
                }
                if (!s.candidates.empty()) {
                    // The point's own scan's unregistered points within mu, or 2 mu where sparse.
                    const std::uint32_t scan = ctx.sight.scan_of(i);
                    auto own_layer = [&](std::span<const NearCube> cubes, double radius) {
                        const auto rr = static_cast<float>(radius * radius);
                        s.layer.clear();
                        for (const NearCube& nc : cubes)
                            for (std::uint32_t j = index.cube_begin(nc.cube);
                                 j < index.cube_end(nc.cube); ++j) {
                                if (labels[j] < 0 && ctx.sight.scan_of(j) == scan && near_p(j, rr))
                                    s.layer.push_back(index.local_point(j));
                            }
                    };
                    own_layer(level_cubes(0), cfg.mu);
                    if (s.layer.size() < static_cast<std::size_t>(kLayerMinPoints))
                        own_layer(level_cubes(1), radii[0]);
                    best =
                        attach_layer(ctx, ray, s.candidates, surfaces, tolerance, s.layer, s.dist);
                }
            }
            if (best >= 0) attach.emplace_back(i, best);
        }
    }
}

}  // namespace

/// Stage 3: each point left unregistered goes to the best-fitting neighbouring surface.
void attach_leftovers(const GrowContext& ctx, std::span<const Slab> slabs,
                      const std::vector<Surface>& surfaces, std::span<const double> tolerance,
                      int threads, std::span<std::int32_t> labels, std::int32_t first_surface) {
    if (std::none_of(labels.begin(), labels.end(), [](std::int32_t l) { return l < 0; })) return;
    const CubeSurfaces near_surfaces =
        cube_surfaces(ctx.index, labels, std::max(first_surface, 0), threads);
    std::vector<LeftoverScratch> scratch(static_cast<std::size_t>(threads));
    std::vector<std::vector<std::pair<std::uint32_t, std::int32_t>>> attach(slabs.size());
    ParallelErrors errors;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::size_t s = 0; s < slabs.size(); ++s) {
        errors.run(s, [&] {
            // Filled here and moved: neighbouring slabs' vectors share a cache line.
            std::vector<std::pair<std::uint32_t, std::int32_t>> found;
            attach_slab(ctx, slabs[s], surfaces, tolerance, near_surfaces,
                        scratch[static_cast<std::size_t>(omp_get_thread_num())], found);
            attach[s] = std::move(found);
        });
    }
    errors.rethrow();
    for (const auto& list : attach)
        for (const auto& [i, sid] : list) labels[i] = sid;
}

}  // namespace surfgrow::detail
