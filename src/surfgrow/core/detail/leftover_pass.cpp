#include "surfgrow/core/detail/leftover_pass.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace surfgrow::detail {

namespace {

// A leftover beside surfaces that it does not fit looks for others up to this many mu away.
constexpr double kMissRadiusPerMu = 2.0;
// Fused clouds: a leftover that lies in another scan's layer of a surface, as far from it as this
// many sigmas of the measured layer offsets, goes to that surface (attach_layer).
constexpr double kLayerSigmas = 3.0;
// ... if at least this many unregistered points of its own scan around it make that layer.
constexpr int kLayerMinPoints = 4;

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
/// to the surface (its distances to the plane agree), and offset from it by at most kLayerSigmas of
/// the measured layer offsets; the point must lie within the surface's tolerance of the layer's
/// median.
std::int32_t attach_layer(const GrowContext& ctx, const Vec3d& ray,
                          std::span<const Candidate> candidates,
                          const std::vector<Surface>& surfaces, std::span<const double> tolerance,
                          std::vector<Vec3f>& layer, std::vector<double>& dist) {
    if (layer.size() < static_cast<std::size_t>(kLayerMinPoints)) return -1;
    const CubeIndex& index = ctx.index;
    const double range = ray.norm();
    if (!(range > 0)) return -1;  // a point on its sensor has no ray
    const double max_spread = ctx.config.thickness_sigmas * ctx.noise.sigma(range);
    std::int32_t best = -1;
    double best_fit = 0;
    for (const Candidate& cand : candidates) {
        const auto sid = static_cast<std::size_t>(cand.surface);
        const Surface& surf = surfaces[sid];
        const Vec3f n = surf.normal.cast<float>();
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

/// Leftover pass: for each unregistered point, the neighbouring surface whose plane it fits best.
/// Reads only labels fixed by growing and writes to `attach`, so slabs can run in any order.
/// Leftovers are a few per cent of the points: their cubes' runs are looked up one cube at a time.
void attach_slab(const GrowContext& ctx, const Slab& slab, const std::vector<Surface>& surfaces,
                 std::span<const double> tolerance, Scratch& s,
                 std::vector<std::pair<std::uint32_t, std::int32_t>>& attach) {
    const CubeIndex& index = ctx.index;
    const GrowerConfig& cfg = ctx.config;
    const std::span<const std::int32_t> labels = ctx.labels;
    const auto r2 = static_cast<float>(cfg.mu * cfg.mu);
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
    std::vector<Candidate> candidates;
    std::vector<double> dist;
    std::vector<Vec3f> layer;
    for (std::uint32_t c = slab.cube_begin; c < slab.cube_end; ++c) {
        s.runs.clear();
        for (auto& runs : s.far_runs) runs.clear();
        // The runs of search level `level` around cube c, looked up on first use.
        auto far_runs = [&](std::size_t level) -> std::span<const Range> {
            if (s.far_runs[level].empty())
                index.column_ranges(index.cube_coords(c),
                                    static_cast<int>(std::ceil(radii[level] / index.cube_size())),
                                    s.far_runs[level]);
            return s.far_runs[level];
        };
        for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
            if (labels[i] >= 0) continue;
            if (s.runs.empty()) index.column_ranges(index.cube_coords(c), 1, s.runs);
            const Vec3f p = index.local_point(i);
            const Vec3d pw = index.origin() + p.cast<double>();
            std::int32_t best = -1;
            double best_dist = 0;
            bool any_neighbour = false;
            // Fused clouds: the surfaces whose plane another layer of it may be off by (at normal
            // incidence; attach_layer applies each one's), for the layer search below.
            candidates.clear();
            const Vec3d ray = layered ? ctx.sight.towards(i, p) : Vec3d::Zero();
            const double layer_reach = layered ? kLayerSigmas * ctx.layers.sigma(ray.norm()) : 0.0;
            auto consider = [&](std::int32_t sid) {
                any_neighbour = true;
                const auto k = static_cast<std::size_t>(sid);
                const Surface& surf = surfaces[k];
                const double signed_d = surf.normal.dot(pw - surf.centroid);
                const double d = std::abs(signed_d);
                if (d <= tolerance[k] && (best < 0 || d < best_dist)) {
                    best = sid;
                    best_dist = d;
                }
                if (layered && tolerance[k] >= 0 && d <= tolerance[k] + layer_reach &&
                    std::none_of(candidates.begin(), candidates.end(),
                                 [&](const Candidate& q) { return q.surface == sid; }))
                    candidates.push_back({sid, signed_d});
            };
            // Neighbours come in runs of one surface: considering a surface again changes nothing.
            std::int32_t last = -1;
            int near = 0;  // points within mu, registered or not
            auto visit = [&](std::uint32_t j) {
                ++near;
                const std::int32_t l = labels[j];
                if (l < 0 || l == last) return;
                consider(l);
                last = l;
            };
            for_each_in_runs_within(index, s.runs, p, r2, visit);
            // Sparse at mu: as far as the adaptive radius reaches. Dense but fitting nothing here
            // (mixed pixels, a rejected edge): only a little farther.
            const bool sparse = !any_neighbour && near < cfg.min_pts;
            if (!any_neighbour || (every_miss && best < 0)) {
                const double limit = sparse || !every_miss ? cfg.max_radius() : miss_limit;
                for (std::size_t level = 0; level < radii.size() && best < 0; ++level) {
                    const double radius = std::min(radii[level], limit);
                    last = -1;
                    for_each_in_runs_within(index, far_runs(level), p,
                                            static_cast<float>(radius * radius), visit);
                    if (radii[level] >= limit) break;
                }
            }
            if (best < 0 && !candidates.empty()) {
                // The point's own scan's unregistered points within mu, or 2 mu where sparse.
                const std::uint32_t scan = ctx.sight.scan_of(i);
                auto gather = [&](std::span<const Range> runs, double radius) {
                    layer.clear();
                    for_each_in_runs_within(index, runs, p, static_cast<float>(radius * radius),
                                            [&](std::uint32_t j) {
                                                if (labels[j] < 0 && ctx.sight.scan_of(j) == scan)
                                                    layer.push_back(index.local_point(j));
                                            });
                };
                gather(s.runs, cfg.mu);
                if (layer.size() < static_cast<std::size_t>(kLayerMinPoints))
                    gather(far_runs(0), radii[0]);
                best = attach_layer(ctx, ray, candidates, surfaces, tolerance, layer, dist);
            }
            if (best >= 0) attach.emplace_back(i, best);
        }
    }
}

}  // namespace

/// Stage 3: each point left unregistered goes to the best-fitting neighbouring surface.
void attach_leftovers(const GrowContext& ctx, std::span<const Slab> slabs,
                      const std::vector<Surface>& surfaces, std::span<const double> tolerance,
                      int threads, std::vector<Scratch>& scratch, std::span<std::int32_t> labels) {
    std::vector<std::vector<std::pair<std::uint32_t, std::int32_t>>> attach(slabs.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::size_t s = 0; s < slabs.size(); ++s) {
        attach_slab(ctx, slabs[s], surfaces, tolerance,
                    scratch[static_cast<std::size_t>(omp_get_thread_num())], attach[s]);
    }
    for (const auto& list : attach)
        for (const auto& [i, sid] : list) labels[i] = sid;
}

}  // namespace surfgrow::detail
