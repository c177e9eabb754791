#include "surfgrow/core/surface_grower.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <initializer_list>
#include <limits>
#include <numeric>
#include <string>
#include <string_view>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/bulk_allocator.hpp"
#include "surfgrow/core/detail/edge_pass.hpp"
#include "surfgrow/core/detail/grow_context.hpp"
#include "surfgrow/core/detail/grow_statistics.hpp"
#include "surfgrow/core/detail/leftover_pass.hpp"
#include "surfgrow/core/detail/neighbourhood.hpp"
#include "surfgrow/core/detail/neighbourhood_fit.hpp"
#include "surfgrow/core/detail/slab_colours.hpp"
#include "surfgrow/core/detail/strip_growing.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/grown_points.hpp"
#include "surfgrow/core/length_limits.hpp"
#include "surfgrow/core/memory_budget.hpp"
#include "surfgrow/core/noise_profile.hpp"
#include "surfgrow/core/plane_pooling.hpp"
#include "surfgrow/core/random.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow {

// The growing's internals: the neighbourhood kernels and the bulk arrays.
using namespace detail;

void validate(const GrowerConfig& c) {
    auto fail = [](std::initializer_list<std::string_view> what) {
        throw Error(ErrorCode::kInvalidParameter, cat(what));
    };
    // Every length first within what float coordinates can express (1e40 once overflowed into a
    // wrong message); then each parameter's own range.
    check_length_range("mu", c.mu);
    check_length_range("plane tolerance", c.plane_tolerance);
    check_length_range("pool radius", c.pool_radius);
    check_length_range("range band", c.range_band);
    if (c.crop.radius) check_length_range("crop radius", *c.crop.radius);
    if (c.crop.box)
        for (int k = 0; k < 3; ++k) {
            check_length_range("crop box corner", c.crop.box->min[k]);
            check_length_range("crop box corner", c.crop.box->max[k]);
        }
    for (int k = 0; k < 3; ++k) {
        if (c.crop.center) check_length_range("crop centre", (*c.crop.center)[k]);
        if (c.viewpoint) check_length_range("viewpoint", (*c.viewpoint)[k]);
    }
    if (!(c.mu > 0) || !std::isfinite(c.mu))
        fail({"mu must be a positive length, got ", num(c.mu)});
    if (c.min_new_points < 1)
        fail({"min-new-points must be at least 1, got ", num(c.min_new_points)});
    if (c.min_pts < 3)
        fail({"min-pts must be at least 3 (a plane needs 3 points), got ", num(c.min_pts)});
    if (c.min_pts > kMaxMinPts)
        fail({"min-pts must be at most ", std::to_string(kMaxMinPts),
              " (more neighbours within mu than any scan holds), got ", std::to_string(c.min_pts)});
    if (!(c.alpha > 1) || !std::isfinite(c.alpha))
        fail({"alpha must be greater than 1 (eq. 2: min(lambda) < mid(lambda) / alpha), got ",
              num(c.alpha)});
    if (!(c.plane_tolerance >= 0) || !std::isfinite(c.plane_tolerance))
        fail({"plane tolerance must be a length >= 0 (0 means mu), got ", num(c.plane_tolerance)});
    if (!(c.adaptive_factor >= 1 && c.adaptive_factor <= 64))
        fail({"the adaptive radius (mu-max) must be between mu (off) and 64 mu, got ",
              num(c.adaptive_factor), " mu"});
    if (!(c.min_spread >= 0 && c.min_spread <= 1))
        fail({"min-spread must lie in [0, 1] (a share of a disk's spread), got ",
              num(c.min_spread)});
    if (!(c.max_incidence_deg > 0 && c.max_incidence_deg <= 90))
        fail({"max-incidence must lie in (0, 90] degrees, got ", num(c.max_incidence_deg)});
    if (!(c.thickness_sigmas >= 1 && c.thickness_sigmas <= 100))
        fail({"thickness-sigmas must lie in [1, 100], got ", num(c.thickness_sigmas)});
    if (!(c.noise_sigmas >= 1 && c.noise_sigmas <= 100))
        fail({"noise-sigmas must lie in [1, 100], got ", num(c.noise_sigmas)});
    if (!(c.pool_angle_deg >= 0 && c.pool_angle_deg < 90))
        fail({"pool-angle must lie in [0, 90) degrees (0: off), got ", num(c.pool_angle_deg)});
    if (!(c.pool_radius >= 0))
        fail({"pool radius must be a length >= 0 (0 means 4 mu), got ", num(c.pool_radius)});
    if (c.threads < 0) fail({"threads must be >= 0 (0 = all cores), got ", num(c.threads)});
    if (!(c.range_band > 0) || !std::isfinite(c.range_band))
        fail({"range band must be a positive length, got ", num(c.range_band)});
    if (c.crop.radius && (!(*c.crop.radius > 0) || !std::isfinite(*c.crop.radius)))
        fail({"crop radius must be a positive length, got ", num(*c.crop.radius)});
    if (c.crop.box &&
        (c.crop.box->empty() || !c.crop.box->min.allFinite() || !c.crop.box->max.allFinite()))
        fail({"crop box must have finite corners with min <= max on every axis"});
}

namespace {

// The frame origin counts as the sensor if it lies within this many box diagonals of the points.
constexpr double kFrameOriginReach = 10.0;
// The noise profile: this many sample neighbourhoods, in range bands of this many mu, and no
// sigma below mu / kNoiseFloorPerMu (float coordinates and 1 mm range steps at mu = 12 mm).
constexpr std::size_t kNoiseSamples = 1536;
constexpr double kNoiseBandPerMu = 25.0;
constexpr double kNoiseFloorPerMu = 24.0;
// A patch with at least this many patches around it, none of them in its plane, is dropped.
constexpr int kLoneNeighbours = 3;
// So is one whose plane holds less than this share of the points of the other planes around it:
// a depth edge's mixed pixels make a ramp one beam footprint wide between two faces, locally a
// plane, outweighed by the faces; a narrow real face is sampled across its width and keeps its
// weight. The study that chose a fifth: docs/algorithm.md.
constexpr double kMinorityShare = 0.2;
// The median of |x| for a zero-mean Gaussian x is this many sigmas.
constexpr double kMedianAbsPerSigma = 0.6745;

/// Cuts the index into slabs along x. Every slab but the first and the last spans at least
/// `min_width` cube columns, so same-colour slabs (every other one) are more than 2*reach apart.
/// Depends only on the data and the parameters, never on the thread count.
std::vector<Slab> partition_slabs(const CubeIndex& index, int min_width,
                                  std::size_t target_points) {
    std::vector<Slab> slabs;
    const std::size_t nc = index.cube_count();
    if (nc == 0) return slabs;
    int x0 = index.cube_coords(0).x();
    std::uint32_t start = 0;
    for (std::size_t c = 1; c < nc; ++c) {
        const int x = index.cube_coords(c).x();
        if (x == index.cube_coords(c - 1).x()) continue;
        const std::size_t points = index.cube_begin(c) - index.cube_begin(start);
        if (x - x0 >= min_width && points >= target_points) {
            slabs.push_back({start, static_cast<std::uint32_t>(c)});
            start = static_cast<std::uint32_t>(c);
            x0 = x;
        }
    }
    slabs.push_back({start, static_cast<std::uint32_t>(nc)});
    return slabs;
}

struct SlabCounters {
    std::uint64_t tried = 0, sparse = 0, nonplanar = 0, covered = 0, adapted = 0;
};

/// Undoes register_points for one home: its label back to "unregistered" wherever it was set,
/// and the points it took from other surfaces back to them.
void unregister_points(std::span<const Range> runs, std::span<std::int32_t> labels,
                       std::span<float> distance, std::int32_t label,
                       std::span<const TakenPoint> taken) {
    for (const Range& run : runs)
        for (std::uint32_t j = run.begin; j < run.end; ++j)
            if (labels[j] == label) labels[j] = -1;
    for (const TakenPoint& t : taken) {
        labels[t.point] = t.label;
        distance[t.point] = t.distance;
    }
}

/// Grows every home point of one slab, in a random order drawn from the slab's own stream.
void grow_slab(const GrowContext& ctx, const Slab& slab, std::size_t slab_id, Scratch& s,
               BulkVector<GrownSurface>& out, SlabCounters& counters) {
    const CubeIndex& index = ctx.index;
    const GrowerConfig& cfg = ctx.config;
    const std::uint32_t p_begin = index.cube_begin(slab.cube_begin);
    const std::uint32_t p_end = index.cube_begin(slab.cube_end);
    s.order.resize(p_end - p_begin);
    std::iota(s.order.begin(), s.order.end(), p_begin);
    SplitMix64 rng(mix_seed(cfg.seed, slab_id));
    shuffle(std::span<std::uint32_t>(s.order), rng);
    index.neighbour_table(slab.cube_begin, slab.cube_end, s.table);

    const bool disk = cfg.plane_test == PlaneTest::kDisk;
    const auto min_new = static_cast<std::uint32_t>(std::max(1, cfg.min_new_points));
    for (const std::uint32_t home : s.order) {
        if (ctx.labels[home] >= 0) continue;
        ++counters.tried;
        const Vec3f h = index.local_point(home);
        // A binary search, not a per-point table: only the homes tried (a few %) need it.
        const std::uint32_t cube = index.cube_of(home, slab.cube_begin, slab.cube_end);
        Neighbourhood nb = fit_neighbourhood(
            ctx, home, h, cube, std::span<const Range>(&s.table[9 * (cube - slab.cube_begin)], 9),
            s.runs);
        if (nb.moments.n < cfg.min_pts) {
            ++counters.sparse;
            continue;
        }
        if (nb.verdict != PlaneVerdict::kPlane) {
            ++counters.nonplanar;
            continue;
        }
        const double radius = nb.radius;
        const double tol = nb.tolerance;
        const PlaneFit& fit = nb.fit;
        const auto label = static_cast<std::int32_t>(home);
        std::uint32_t registered = 0;
        s.taken.clear();
        if (disk) {
            registered = register_best_fit(index, nb.runs, h, static_cast<float>(radius),
                                           fit.normal.cast<float>(), fit.centroid.cast<float>(),
                                           static_cast<float>(tol), ctx.labels, ctx.distance, label,
                                           s.taken);
        } else {
            registered = register_points(index, nb.runs, h, static_cast<float>(radius),
                                         fit.normal.cast<float>(), fit.centroid.cast<float>(),
                                         static_cast<float>(tol), ctx.labels, label);
        }
        if (registered < min_new) {
            // The home sits in a gap between earlier surfaces: a new surface would duplicate
            // them. Undo; the leftover pass gives these points to the surface they fit best.
            if (registered > 0 || !s.taken.empty())
                unregister_points(nb.runs, ctx.labels, ctx.distance, label, s.taken);
            ++counters.covered;
            continue;
        }
        if (radius > cfg.mu) ++counters.adapted;
        out.push_back({home, static_cast<float>(radius), static_cast<float>(tol),
                       static_cast<std::uint32_t>(nb.moments.n), fit, nb.moments});
    }
}

/// Fused clouds: how far each scan's layer of a neighbourhood lies from the layer of the scan with
/// the most points there (the mean distances of their points from its plane; scans with at least
/// 3 points), along that scan's rays, as a sample at that scan's range, appended to `out`. A fused
/// cloud is a stack of layers: each scan sees a surface a little off (its range bias for that
/// surface, its pose error), farther apart than the noise within one scan's layer; a surface
/// grown mostly from one layer leaves the others' points beside it. A sample is |offset| divided
/// by kMedianAbsPerSigma, so that the profile's median is the offsets' sigma.
void layer_offsets(const GrowContext& ctx, const Vec3f& h, const Neighbourhood& nb,
                   std::vector<ThicknessSample>& out) {
    struct Layer {
        std::uint32_t scan;
        std::uint32_t point;  // one of its points, for its range
        double sum;
        std::uint32_t count;
    };
    std::vector<Layer> layers;
    const Vec3f n = nb.fit.normal.cast<float>();
    const Vec3f c = h + nb.fit.centroid.cast<float>();
    const auto r = static_cast<float>(nb.radius);
    for_each_in_runs_within(ctx.index, nb.runs, h, r * r, [&](std::uint32_t j) {
        const std::uint32_t scan = ctx.sight.scan_of(j);
        const auto d = static_cast<double>(n.dot(ctx.index.local_point(j) - c));
        auto it = std::find_if(layers.begin(), layers.end(),
                               [&](const Layer& l) { return l.scan == scan; });
        if (it == layers.end()) {
            layers.push_back({scan, j, d, 1});
        } else {
            it->sum += d;
            ++it->count;
        }
    });
    const auto kept =
        std::count_if(layers.begin(), layers.end(), [](const Layer& l) { return l.count >= 3; });
    if (kept < 2) return;
    const Layer& main =
        *std::max_element(layers.begin(), layers.end(), [](const Layer& a, const Layer& b) {
            return a.count < b.count || (a.count == b.count && a.scan > b.scan);
        });
    const double main_offset = main.sum / main.count;
    for (const Layer& l : layers) {
        if (l.count < 3 || &l == &main) continue;
        const Vec3d ray = ctx.sight.towards(l.point, ctx.index.local_point(l.point));
        const double range = ray.norm();
        if (!(range > 0)) continue;  // a point on its sensor has no ray
        const double along = std::max(std::abs(nb.fit.normal.dot(ray)) / range, kMinLayerCos);
        out.push_back(
            {range, std::abs(l.sum / l.count - main_offset) / along / kMedianAbsPerSigma});
    }
}

/// The noise profile of the cloud: the thickness of neighbourhoods around evenly spread sample
/// points that pass the relative tests (no thickness limit yet), by range; and for a fused cloud
/// the profile of its layers' offsets in the same neighbourhoods. Deterministic: the samples
/// depend on the index alone.
NoiseProfile measure_noise(const GrowContext& ctx, int threads, NoiseProfile& layer_profile) {
    const CubeIndex& index = ctx.index;
    const std::size_t n = index.size();
    const std::size_t count = std::min<std::size_t>(n, kNoiseSamples);
    std::vector<ThicknessSample> samples(count);
    std::vector<std::vector<ThicknessSample>> offsets(count);
    std::vector<std::uint8_t> ok(count, 0);
    const bool fused = ctx.sight.fused();
#pragma omp parallel num_threads(threads)
    {
        std::vector<Range> runs27, wide;
#pragma omp for schedule(dynamic, 64)
        for (std::size_t k = 0; k < count; ++k) {
            const auto home = static_cast<std::uint32_t>(k * n / count);
            const Vec3f h = index.local_point(home);
            const std::uint32_t cube = index.cube_of(home);
            runs27.clear();
            index.column_ranges(index.cube_coords(cube), 1, runs27);
            const Neighbourhood nb = fit_neighbourhood(ctx, home, h, cube, runs27, wide);
            if (nb.verdict != PlaneVerdict::kPlane) continue;
            samples[k] = {nb.range, std::sqrt(nb.fit.eigenvalues[0])};
            ok[k] = 1;
            if (fused) layer_offsets(ctx, h, nb, offsets[k]);
        }
    }
    std::vector<ThicknessSample> kept, kept_offsets;
    for (std::size_t k = 0; k < count; ++k) {
        if (ok[k]) kept.push_back(samples[k]);
        kept_offsets.insert(kept_offsets.end(), offsets[k].begin(), offsets[k].end());
    }
    const double band = kNoiseBandPerMu * ctx.config.mu;
    const double floor = ctx.config.mu / kNoiseFloorPerMu;
    layer_profile = NoiseProfile(kept_offsets, band, floor);
    return NoiseProfile(kept, band, floor);
}

Orientation choose_orientation(const CloudView& cloud, const GrowerConfig& cfg, const Aabb& box) {
    if (cloud.has_scan_index() && !cloud.scan_origins.empty())
        return {OrientationSource::kScanOrigins, Vec3d::Zero()};  // no single origin
    if (cfg.viewpoint) return {OrientationSource::kViewpoint, *cfg.viewpoint};
    if (cloud.viewpoint) return {OrientationSource::kViewpoint, *cloud.viewpoint};
    // A scan in its sensor's frame has the frame origin near its points (within a few extents);
    // a georeferenced survey has it thousands of extents away. Near: face the origin. Far: assume
    // an overhead sensor and face +z.
    const Vec3d frame_origin = -cloud.offset;
    if (!box.empty()) {
        const Vec3d nearest = frame_origin.cwiseMax(box.min).cwiseMin(box.max);
        if ((frame_origin - nearest).norm() <=
            kFrameOriginReach * std::max(box.size().norm(), 1e-9))
            return {OrientationSource::kFrameOrigin, frame_origin};
    }
    return {OrientationSource::kUp, Vec3d::Zero()};
}

// ---- The stages of SurfaceGrower::grow, in the order it runs them.

using ProgressReport = std::function<void(std::string_view, double)>;

/// Where the sensor stood for each point, from the chosen orientation.
SensorSight sight_of(const CloudView& cloud, const Orientation& orient, const CubeIndex& index) {
    SensorSight sight;
    if (orient.source == OrientationSource::kScanOrigins) {
        for (const Vec3d& o : cloud.scan_origins) sight.origins.push_back(index.to_local(o));
        sight.scan_index = cloud.scan_index;
        sight.original = index.original_indices();
        sight.named = true;
    } else if (orient.range_known()) {
        sight.origins.push_back(index.to_local(orient.origin));
        sight.named = orient.source == OrientationSource::kViewpoint;
    }
    return sight;
}

/// Stage 2a, the paper's loop: grows every slab, even colour then odd, and returns the surfaces
/// in id order (slab order, then home order within a slab). Frees the scratch's growing buffers.
BulkVector<GrownSurface> grow_slabs(const GrowContext& ctx, std::span<const Slab> slabs,
                                    int threads, std::vector<Scratch>& scratch, GrowStats& st,
                                    const ProgressReport& report) {
    // Where each slab's surfaces lie: thread t's scratch.grown[begin, end).
    struct GrownSpan {
        std::size_t thread = 0, begin = 0, end = 0;
    };
    std::vector<GrownSpan> grown(slabs.size());
    std::vector<SlabCounters> counters(slabs.size());
    std::atomic<std::size_t> done{0};
    // A progress callback may throw to stop the run (Ctrl-C in Python): nothing may leave an
    // OpenMP region, so the first exception is kept, the slabs not yet begun are skipped, and it
    // is thrown again after the region. Only thread 0 reports, so only it writes `stopped_by`.
    std::atomic<bool> stop{false};
    std::exception_ptr stopped_by;
    for (int colour = 0; colour < 2 && !stopped_by; ++colour) {
        for_each_slab_of_colour(ctx.index, slabs, colour, threads, [&](std::size_t s, int t) {
            if (stop.load(std::memory_order_relaxed)) return;
            Scratch& sc = scratch[static_cast<std::size_t>(t)];
            const std::size_t begin = sc.grown.size();
            grow_slab(ctx, slabs[s], s, sc, sc.grown, counters[s]);
            grown[s] = {static_cast<std::size_t>(t), begin, sc.grown.size()};
            const std::size_t d = ++done;
            if (t != 0) return;
            try {
                report("grow", double(d) / double(slabs.size()));
            } catch (...) {
                stopped_by = std::current_exception();
                stop.store(true, std::memory_order_relaxed);
            }
        });
    }
    if (stopped_by) std::rethrow_exception(stopped_by);
    // Surface ids follow the home points' sorted order: slab order, then home order within a slab.
    // Each slab's surfaces go straight to their final place, slabs in parallel.
    std::vector<std::size_t> first(slabs.size() + 1, 0);
    for (std::size_t s = 0; s < slabs.size(); ++s) {
        first[s + 1] = first[s] + (grown[s].end - grown[s].begin);
        st.homes_tried += counters[s].tried;
        st.rejected_sparse += counters[s].sparse;
        st.rejected_nonplanar += counters[s].nonplanar;
        st.rejected_covered += counters[s].covered;
        st.adapted_surfaces += counters[s].adapted;
    }
    BulkVector<GrownSurface> all(first.back());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4)
    for (std::size_t s = 0; s < slabs.size(); ++s) {
        const std::span<const GrownSurface> mine(
            scratch[grown[s].thread].grown.data() + grown[s].begin, grown[s].end - grown[s].begin);
        std::vector<std::pair<std::uint32_t, std::uint32_t>> order(mine.size());  // (home, k)
        for (std::size_t k = 0; k < mine.size(); ++k)
            order[k] = {mine[k].home, static_cast<std::uint32_t>(k)};
        std::sort(order.begin(), order.end());
        for (std::size_t r = 0; r < order.size(); ++r) all[first[s] + r] = mine[order[r].second];
    }
    // The growing's buffers (a slab's worth each) are not needed again: free them before the
    // pooling, which is where small clouds reach their peak.
    for (Scratch& sc : scratch) {
        release(sc.grown);
        release(sc.order);
        release(sc.table);
    }
    return all;
}

/// Every label left after growing is the home of a kept surface (undone homes reset theirs):
/// relabels through a home-to-surface table, read only at those homes. Called after the thread
/// buffers are freed, so that the table does not add to the peak.
void label_by_surface(std::span<std::int32_t> labels, std::span<const GrownSurface> all,
                      int threads) {
    BulkVector<std::int32_t> sid_of_home(labels.size());
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t k = 0; k < all.size(); ++k)
        sid_of_home[all[k].home] = static_cast<std::int32_t>(k);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (labels[i] >= 0) labels[i] = sid_of_home[static_cast<std::size_t>(labels[i])];
    }
}

/// The reported surfaces of the grown ones (statistics come later), with each one's home (sorted
/// index) and registration tolerance (both sized like `all`).
void surfaces_of(std::span<const GrownSurface> all, const CubeIndex& index, int threads,
                 std::vector<Surface>& surfaces, std::span<std::uint32_t> home_of,
                 std::span<double> tolerance) {
    const std::size_t count = all.size();
    surfaces.resize(count);  // within the room grow() reserved
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t k = 0; k < count; ++k) {
        const GrownSurface& g = all[k];
        home_of[k] = g.home;
        Surface& s = surfaces[k];
        s.home = index.world_point(g.home);
        s.centroid = s.home + g.fit.centroid;
        s.normal = g.fit.normal;
        s.eigenvalues = g.fit.eigenvalues;
        s.radius = static_cast<double>(g.radius);
        s.neighbours = g.neighbours;
        s.tolerance = static_cast<double>(g.tolerance);
        tolerance[k] = static_cast<double>(g.tolerance);
    }
}

/// Stage 2b, normal refinement: pools each surface's normal with its neighbours' in the same
/// plane, drops lone patches tilted across an edge (tolerance -1: they hold nothing) and releases
/// members the refined planes no longer hold. Frees `all`.
void refine_normals(const GrowerConfig& cfg, const CubeIndex& index, int threads,
                    BulkVector<GrownSurface>& all, std::vector<Surface>& surfaces,
                    std::vector<double>& tolerance, std::span<std::int32_t> labels, GrowStats& st) {
    const std::size_t surface_count = surfaces.size();
    BulkVector<PoolablePatch> patches(surface_count);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t k = 0; k < surface_count; ++k) {
        const Surface& s = surfaces[k];
        patches[k] = {s.home, s.centroid, s.normal, s.eigenvalues[0], all[k].moments};
    }
    release(all);  // its moments are in the patches now: free them before pooling's own copy
    PoolingConfig pc;
    pc.radius = cfg.pooling_radius();
    pc.max_angle = cfg.pool_angle_deg * M_PI / 180.0;
    pc.min_offset = cfg.mu / 10;
    pc.max_offset = cfg.mu / 2;
    pc.threads = threads;
    std::vector<std::uint8_t> lone;
    const std::vector<Vec3d> pooled =
        pool_normals(patches, pc, lone,
                     cfg.plane_test == PlaneTest::kDisk ? LoneRule{kLoneNeighbours, kMinorityShare}
                                                        : LoneRule{});
    release(patches);
    for (std::size_t k = 0; k < surface_count; ++k) surfaces[k].normal = pooled[k];
    // A patch in no plane with its neighbours is a fit tilted across an edge: its members go to
    // the leftover pass, which gives each to the neighbouring surface it fits best.
    if (!lone.empty()) {
        std::uint64_t dropped = 0;
        for (std::size_t k = 0; k < surface_count; ++k) {
            if (!lone[k]) continue;
            tolerance[k] = -1;  // holds nothing
            ++dropped;
        }
        st.lone_surfaces = dropped;
    }
    // A reported plane must hold its members: release any the refined plane no longer fits
    // (rare: points at the tolerance's edge); the leftover pass may re-attach them.
    std::uint64_t released = 0;
    const std::vector<LocalPlane> planes = local_planes(index, surfaces, tolerance);
    const std::size_t n = labels.size();
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : released)
    for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t l = labels[i];
        if (l < 0) continue;
        if (!planes[static_cast<std::size_t>(l)].holds(
                index.local_point(static_cast<std::uint32_t>(i)))) {
            labels[i] = -1;
            ++released;
        }
    }
    st.released_by_refinement = released;
}

/// A mu finer than the float coordinates resolve at every point of the cloud cannot tell any
/// neighbours apart (1e-300 m once reached the index as billions of cubes): a wrong unit or a
/// typo, refused as the mu beyond the whole cloud is. Where some points resolve it (a cloud far
/// larger than mu around the origin), growing there still means something and is left alone.
void refuse_mu_below_resolution(const CloudView& cloud, const WorkspaceMask& workspace, double mu,
                                int threads) {
    float nearest = std::numeric_limits<float>::infinity();  // the smallest largest |coordinate|
#pragma omp parallel for num_threads(threads) schedule(static) reduction(min : nearest)
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
        const Vec3f& p = cloud.points[i];
        if (!is_finite(p) || (!workspace.inside.empty() && !workspace.inside[i])) continue;
        nearest = std::min(nearest, p.cwiseAbs().maxCoeff());
    }
    if (!std::isfinite(nearest)) return;  // no points: nothing to resolve
    const double step =
        double(std::nextafter(nearest, std::numeric_limits<float>::infinity()) - nearest);
    if (mu < step) {
        char where[80];
        std::snprintf(where, sizeof where,
                      "a step of %.3g even at its point nearest the origin, %.4g", step,
                      double(nearest));
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"mu = ", num(mu), " is finer than the cloud's float coordinates resolve (",
                         where, "); check mu and the cloud's units"}));
    }
}

}  // namespace

SurfaceGrower::SurfaceGrower(GrowerConfig config) : config_(std::move(config)) {
    validate(config_);
}

GrowIndex SurfaceGrower::index(const CloudView& cloud) const {
    Stopwatch watch;
    WorkspaceMask workspace = workspace_mask(cloud, config_);
    // A clear error before the allocations rather than the OOM killer half way: the labels and
    // distances of every point, and per indexed point the cube index, its sorted coordinates
    // and the growing's buffers (53 B measured on 10^6 points; 64 with a margin).
    const std::uint64_t indexed = cloud.size() - workspace.cropped;  // at most: NaNs are not
    check_memory(8.0 * double(cloud.size()) + 64.0 * double(indexed),
                 cat({"growing ", std::to_string(indexed), " points"}));
    refuse_mu_below_resolution(cloud, workspace, config_.mu, resolve_threads(config_.threads));
    GrowIndex g;
    g.index =
        CubeIndex(cloud.points, config_.mu, workspace.inside, resolve_threads(config_.threads));
    // A mu beyond the whole cloud makes every neighbourhood the whole cloud: nothing can come of
    // it but a long wait (minutes at 1e3 m on a room), so it is a wrong unit or a typo.
    const double diagonal = g.index.bounds().size().norm();
    if (g.index.size() >= 2 && diagonal > 0 && config_.mu > diagonal)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"mu = ", num(config_.mu),
                         " is larger than the whole cloud (the diagonal "
                         "of its points' bounding box is ",
                         num(std::round(diagonal * 1e3) / 1e3),
                         "): every neighbourhood would hold every point; check mu and the cloud's "
                         "units"}));
    g.points = cloud.points.size();
    g.cropped_points = workspace.cropped;
    g.seconds = watch.seconds();
    return g;
}

GrowResult SurfaceGrower::grow(const CloudView& cloud) const {
    return grow(cloud, index(cloud));
}

GrowResult SurfaceGrower::grow(const CloudView& cloud, const GrowIndex& grow_index) const {
    const GrowerConfig& cfg = config_;
    const int threads = resolve_threads(cfg.threads);
    GrowResult result;
    GrowStats& st = result.stats;
    const std::size_t n_in = cloud.points.size();
    if (grow_index.points != n_in)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"the cube index was built over ", std::to_string(grow_index.points),
                         " points, not over this cloud of ", std::to_string(n_in)}));
    st.points_in = n_in;
    const ProgressReport report = [&](std::string_view stage, double f) {
        if (cfg.progress) cfg.progress(stage, f);
    };

    // --- Stage 1: the cube index over valid points inside the crop (index()).
    const CubeIndex& index = grow_index.index;
    const std::size_t n = index.size();
    st.cropped_points = grow_index.cropped_points;
    st.valid_points = n;
    st.invalid_points = n_in - n - st.cropped_points;
    st.seconds.index = grow_index.seconds;
    report("index", 1.0);
    Stopwatch stage;

    // --- Stage 2: growing, slab by slab, even colour then odd; then normal refinement.
    const int reach = static_cast<int>(std::ceil(cfg.max_radius() / index.cube_size()));
    const std::size_t target = std::clamp<std::size_t>(n / 256, 4096, 65536);
    const std::vector<Slab> slabs = partition_slabs(index, 2 * reach, target);
    BulkVector<std::int32_t> labels(n, -1);
    // Best-fit registration keeps each registered point's distance to its plane.
    BulkVector<float> distance(cfg.plane_test == PlaneTest::kDisk ? n : 0);
    const Orientation orient = choose_orientation(cloud, cfg, index.bounds());
    const SensorSight sight = sight_of(cloud, orient, index);
    std::vector<Scratch> scratch(static_cast<std::size_t>(threads));
    // About one surface per 30 points in scans at the paper's mu; a buffer that fills up doubles.
    // Kept under 2 MiB for small clouds, where a huge page would mostly stay empty.
    for (Scratch& sc : scratch) sc.grown.reserve(n / (32 * scratch.size()) + 64);
    NoiseProfile noise, layers;
    const GrowContext sampling{index, cfg, labels, distance, sight, noise, layers};
    if (cfg.plane_test == PlaneTest::kDisk) noise = measure_noise(sampling, threads, layers);
    st.noise_band = noise.band();
    st.noise_sigma = noise.sigmas();
    st.layer_band = layers.band();
    st.layer_sigma = layers.sigmas();
    const GrowContext ctx{index, cfg, labels, distance, sight, noise, layers};
    BulkVector<GrownSurface> all = grow_slabs(ctx, slabs, threads, scratch, st, report);
    label_by_surface(labels, all, threads);
    const std::size_t surface_count = all.size();
    // Strips (stage 3b) are grown with the disk test, not in fused clouds: their leftovers are
    // mostly other scans' layers and mixed pixels (there strips added 0.01-0.03 % of
    // registration, serially; docs/algorithm.md). Room for them from the start: growing the
    // vectors later copies every surface into fresh pages, which cost 7 ms of a 75 ms growing in
    // this VM. A strip's first ball holds min_pts leftovers; room never touched costs no memory.
    // The disk test's passes after growing (the leftovers, surfaces reaching along their faces,
    // the edge pass); strips among them only where scans are not fused.
    const bool disk_passes = cfg.plane_test == PlaneTest::kDisk && cfg.attach_leftovers;
    const bool strips = disk_passes && !sight.fused();
    const std::size_t room =
        surface_count +
        (strips ? static_cast<std::size_t>(std::count(labels.begin(), labels.end(), -1)) /
                          static_cast<std::size_t>(std::max(cfg.min_pts, 1)) +
                      64
                : 0);
    reserve_bulk(result.surfaces, room);
    std::vector<std::uint32_t> home_of;  // sorted index of each surface's home
    std::vector<double> tolerance;
    home_of.reserve(room);
    tolerance.reserve(room);
    home_of.resize(surface_count);
    tolerance.resize(surface_count);
    surfaces_of(all, index, threads, result.surfaces, home_of, tolerance);
    if (cfg.pool_angle_deg > 0 && surface_count > 0)
        refine_normals(cfg, index, threads, all, result.surfaces, tolerance, labels, st);
    release(all);
    release(distance);  // best-fit registration is over: the later stages do not read it
    st.seconds.grow = stage.lap();
    for (const std::int32_t l : labels) st.registered_grown += l >= 0 ? 1 : 0;

    // --- Stage 3: attach leftovers to the best-fitting neighbouring surface.
    const GrowContext late{index, cfg, labels, {}, sight, noise, layers};  // distances released
    // The points growing left unregistered (a byte each): stage 3b's last step reaches on from
    // those the later stages register.
    std::vector<std::uint8_t> was_left(disk_passes ? n : 0, 0);
    for (std::size_t i = 0; i < was_left.size(); ++i) was_left[i] = labels[i] < 0 ? 1 : 0;
    if (cfg.attach_leftovers && surface_count > 0)
        attach_leftovers(late, slabs, result.surfaces, tolerance, threads, labels);
    // --- Stage 3b: strips narrower than a ball, from the points no surface fits (`strips`: where).
    if (strips)
        st.strip_surfaces = grow_strips(late, slabs, threads, result.surfaces, home_of, tolerance);
    // ... and a strip's plane reaches beyond its ball: the points still left go to the strip
    // they fit best, by the leftover pass's rules (no other surface fits them: the pass before).
    if (st.strip_surfaces > 0) {
        const auto first_strip =
            static_cast<std::int32_t>(result.surfaces.size() - st.strip_surfaces);
        attach_leftovers(late, slabs, result.surfaces, tolerance, threads, labels, first_strip);
        // ... and farther along its face, step by step (the far ends of a flange's edge).
        extend_strips(late, first_strip, result.surfaces, tolerance);
    }
    // ... and every surface reaches along its face as strips do, from the points registered since
    // growing (a far wall at grazing incidence; in fused clouds too, where no strips grow).
    if (disk_passes) {
        std::vector<std::uint32_t> frontier;
        for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(n); ++i)
            if (was_left[i] && labels[i] >= 0) frontier.push_back(i);
        release(was_left);
        extend_surfaces(late, result.surfaces, tolerance, std::move(frontier));
    }
    // --- Stage 3c (fused clouds): points along edges to the face their own scan's layer fits.
    if (disk_passes && surface_count > 0)
        st.edge_moves = reassign_at_edges(late, slabs, result.surfaces, tolerance, threads, labels);
    st.seconds.attach = stage.lap();
    report("attach", 1.0);

    // --- Stage 4: member statistics, labels in input order, range bands, orientation.
    st.orientation = orient.source;
    st.range_known = orient.range_known();
    st.range_origin = orient.origin;
    // Labels in input order. Points not in the index (invalid, cropped) are marked first, so
    // that the range bands can stream the input in its own order and skip them.
    const auto orig = index.original_indices();
    reserve_bulk(result.labels, n_in);
    result.labels.assign(n_in, kNotIndexed);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < n; ++i) result.labels[orig[i]] = labels[i];
    st.registered = member_statistics(index, labels, tolerance, threads, result.surfaces);
    st.noise_points = st.valid_points - st.registered;
    st.range_bands = range_bands(cloud, orient, cfg.range_band, threads, result.labels);
    st.edge_on_points = orient_normals(cloud, orient, orig, home_of, cfg.max_incidence_deg, threads,
                                       result.surfaces);
    st.dropped_surfaces = drop_empty_surfaces(threads, result.surfaces, result.labels);
    st.surfaces = result.surfaces.size();
    st.seconds.finish = stage.lap();
    report("finish", 1.0);
    return result;
}

}  // namespace surfgrow
