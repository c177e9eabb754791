#include "surfgrow/core/surface_grower.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numeric>
#include <string>
#include <string_view>

#include "surfgrow/core/bulk_allocator.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/neighbourhood.hpp"
#include "surfgrow/core/plane_pooling.hpp"
#include "surfgrow/core/random.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

void validate(const GrowerConfig& c) {
    auto fail = [](std::initializer_list<std::string_view> what) {
        throw Error(ErrorCode::kInvalidParameter, cat(what));
    };
    if (!(c.mu > 0) || !std::isfinite(c.mu))
        fail({"mu must be a positive length, got ", num(c.mu)});
    if (c.min_new_points < 1)
        fail({"min-new-points must be at least 1, got ", num(c.min_new_points)});
    if (c.min_pts < 3)
        fail({"min-pts must be at least 3 (a plane needs 3 points), got ", num(c.min_pts)});
    if (!(c.alpha > 1) || !std::isfinite(c.alpha))
        fail({"alpha must be greater than 1 (eq. 2: min(lambda) < mid(lambda) / alpha), got ",
              num(c.alpha)});
    if (!(c.plane_tolerance >= 0) || !std::isfinite(c.plane_tolerance))
        fail({"plane tolerance must be a length >= 0 (0 means mu), got ", num(c.plane_tolerance)});
    if (!(c.adaptive_factor >= 1 && c.adaptive_factor <= 64))
        fail({"the adaptive radius (mu-max) must be between mu (off) and 64 mu, got ",
              num(c.adaptive_factor), " mu"});
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

using Clock = std::chrono::steady_clock;
constexpr std::size_t kMaxRangeBands = 1024;
// The frame origin counts as the sensor if it lies within this many box diagonals of the points.
constexpr double kFrameOriginReach = 10.0;
using Range = CubeIndex::Range;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// A slab: all cubes whose x coordinate lies in one interval; a contiguous run of cubes.
struct Slab {
    std::uint32_t cube_begin = 0;
    std::uint32_t cube_end = 0;
};

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

/// A surface as it is grown, before statistics: home (sorted index), radius, fit.
struct GrownSurface {
    std::uint32_t home = 0;
    float radius = 0;
    std::uint32_t neighbours = 0;
    PlaneFit fit;     // centroid relative to the home point, local frame
    Moments moments;  // about the home point, for normal pooling
};

struct SlabCounters {
    std::uint64_t tried = 0, sparse = 0, nonplanar = 0, covered = 0, adapted = 0;
};

/// Undoes register_points for one home: its label back to "unregistered" wherever it was set.
void unregister_points(std::span<const Range> runs, std::span<std::int32_t> labels,
                       std::int32_t label) {
    for (const Range& run : runs)
        for (std::uint32_t j = run.begin; j < run.end; ++j)
            if (labels[j] == label) labels[j] = -1;
}

/// Per-thread scratch reused across slabs: no allocation per home point.
struct Scratch {
    BulkVector<GrownSurface> grown;  // every slab this thread grew, one after another
    std::vector<std::uint32_t> order;
    std::vector<Range> table;
    std::vector<Range> runs;
    std::vector<Range> far_runs;  // the leftover pass's wider search, per cube
};

struct GrowContext {
    const CubeIndex& index;
    const GrowerConfig& config;
    std::span<std::int32_t> labels;  // sorted order; during growing: the home's sorted index
};

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

    const auto mu = static_cast<float>(cfg.mu);
    const double max_radius = cfg.max_radius();
    const double tol_per_radius = cfg.tolerance() / cfg.mu;
    const auto min_new = static_cast<std::uint32_t>(std::max(1, cfg.min_new_points));
    for (const std::uint32_t home : s.order) {
        if (ctx.labels[home] >= 0) continue;
        ++counters.tried;
        const Vec3f h = index.local_point(home);
        // A binary search, not a per-point table: only the homes tried (a few %) need it.
        const std::uint32_t cube = index.cube_of(home, slab.cube_begin, slab.cube_end);
        std::span<const Range> runs(&s.table[9 * (cube - slab.cube_begin)], 9);
        double radius = cfg.mu;
        Moments m = gather_moments(index, runs, h, mu);
        // Adaptive radius: double it while the support is too thin, up to the adaptive maximum.
        while (m.n < cfg.min_pts && radius < max_radius) {
            radius = std::min(2.0 * radius, max_radius);
            s.runs.clear();
            index.column_ranges(index.cube_coords(cube),
                                static_cast<int>(std::ceil(radius / index.cube_size())), s.runs);
            runs = s.runs;
            m = gather_moments(index, runs, h, static_cast<float>(radius));
        }
        if (m.n < cfg.min_pts) {
            ++counters.sparse;
            continue;
        }
        // Most edge and clutter neighbourhoods fail eq. (2) plainly: the cubic's eigenvalues say so
        // at a third of the full solve's cost.
        if (clearly_not_planar(m, cfg.alpha)) {
            ++counters.nonplanar;
            continue;
        }
        const PlaneFit fit = fit_plane(m);
        if (!is_planar(fit.eigenvalues, cfg.alpha)) {
            ++counters.nonplanar;
            continue;
        }
        const auto tol = static_cast<float>(tol_per_radius * radius);
        const std::uint32_t registered = register_points(
            index, runs, h, static_cast<float>(radius), fit.normal.cast<float>(),
            fit.centroid.cast<float>(), tol, ctx.labels, static_cast<std::int32_t>(home));
        if (registered < min_new) {
            // The home sits in a gap between earlier surfaces: a new surface would duplicate
            // them. Undo; the leftover pass gives these points to the surface they fit best.
            if (registered > 0)
                unregister_points(runs, ctx.labels, static_cast<std::int32_t>(home));
            ++counters.covered;
            continue;
        }
        if (radius > cfg.mu) ++counters.adapted;
        out.push_back({home, static_cast<float>(radius), static_cast<std::uint32_t>(m.n), fit, m});
    }
}

/// Runs f(slab_id, thread_id) over the slabs of one colour (0: even, 1: odd) in parallel, the
/// largest first (fewer threads idle at the colour's end). Slabs of one colour are independent,
/// so the order changes nothing in the result.
template <class F>
void for_each_slab_of_colour(const CubeIndex& index, std::span<const Slab> slabs, int colour,
                             int threads, F&& f) {
    std::vector<std::uint32_t> ids;
    for (std::size_t s = static_cast<std::size_t>(colour); s < slabs.size(); s += 2)
        ids.push_back(static_cast<std::uint32_t>(s));
    auto points = [&](std::uint32_t s) {
        return index.cube_begin(slabs[s].cube_end) - index.cube_begin(slabs[s].cube_begin);
    };
    std::stable_sort(ids.begin(), ids.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return points(a) > points(b); });
    const auto count = static_cast<std::int64_t>(ids.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::int64_t k = 0; k < count; ++k) {
        f(std::size_t{ids[static_cast<std::size_t>(k)]}, omp_get_thread_num());
    }
}

/// Leftover pass: for each unregistered point, the neighbouring surface whose plane it fits best.
/// Reads only labels fixed by growing and writes to `attach`, so slabs can run in any order.
/// Leftovers are a few per cent of the points: their cubes' runs are looked up one cube at a time.
void attach_slab(const CubeIndex& index, const GrowerConfig& cfg, const Slab& slab,
                 std::span<const std::int32_t> labels, const std::vector<Surface>& surfaces,
                 std::span<const double> tolerance, Scratch& s,
                 std::vector<std::pair<std::uint32_t, std::int32_t>>& attach) {
    const auto r2 = static_cast<float>(cfg.mu * cfg.mu);
    const double far_radius = cfg.max_radius();
    const auto far_r2 = static_cast<float>(far_radius * far_radius);
    const int far_reach = static_cast<int>(std::ceil(far_radius / index.cube_size()));
    for (std::uint32_t c = slab.cube_begin; c < slab.cube_end; ++c) {
        s.runs.clear();
        s.far_runs.clear();
        for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
            if (labels[i] >= 0) continue;
            if (s.runs.empty()) index.column_ranges(index.cube_coords(c), 1, s.runs);
            const Vec3f p = index.local_point(i);
            const Vec3d pw = index.origin() + p.cast<double>();
            std::int32_t best = -1;
            double best_dist = 0;
            bool any_neighbour = false;
            auto consider = [&](std::int32_t sid) {
                any_neighbour = true;
                const Surface& surf = surfaces[static_cast<std::size_t>(sid)];
                const double d = std::abs(surf.normal.dot(pw - surf.centroid));
                if (d <= tolerance[static_cast<std::size_t>(sid)] && (best < 0 || d < best_dist)) {
                    best = sid;
                    best_dist = d;
                }
            };
            // Neighbours come in runs of one surface: considering a surface again changes nothing.
            std::int32_t last = -1;
            auto visit = [&](std::uint32_t j) {
                const std::int32_t l = labels[j];
                if (l < 0 || l == last) return;
                consider(l);
                last = l;
            };
            for_each_in_runs_within(index, s.runs, p, r2, visit);
            if (!any_neighbour && far_radius > cfg.mu) {
                // Isolated at mu: the adaptive radius's reach. Its columns serve the whole cube.
                if (s.far_runs.empty())
                    index.column_ranges(index.cube_coords(c), far_reach, s.far_runs);
                for_each_in_runs_within(index, s.far_runs, p, far_r2, visit);
            }
            if (best >= 0) attach.emplace_back(i, best);
        }
    }
}

/// A surface's plane in the index's float frame, for per-point passes.
struct LocalPlane {
    Vec3f normal;
    float offset;     // normal . centroid (local)
    float tolerance;  // registration tolerance of this surface
    [[nodiscard]] float distance(const Vec3f& p) const { return std::abs(normal.dot(p) - offset); }
    [[nodiscard]] bool holds(const Vec3f& p) const { return distance(p) <= tolerance; }
};

std::vector<LocalPlane> local_planes(const CubeIndex& index, const std::vector<Surface>& surfaces,
                                     std::span<const double> tolerance) {
    std::vector<LocalPlane> planes(surfaces.size());
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
        const Vec3f n = surfaces[k].normal.cast<float>();
        planes[k] = {n, n.dot(index.to_local(surfaces[k].centroid)),
                     static_cast<float>(tolerance[k])};
    }
    return planes;
}

/// Chooses where normals should face and where ranges are measured from.
struct Orientation {
    OrientationSource source = OrientationSource::kUp;
    Vec3d origin = Vec3d::Zero();  // single origin (viewpoint or frame origin)
};

Orientation choose_orientation(const PointCloud& cloud, const GrowerConfig& cfg, const Aabb& box) {
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

}  // namespace

SurfaceGrower::SurfaceGrower(GrowerConfig config) : config_(std::move(config)) {
    validate(config_);
}

GrowResult SurfaceGrower::grow(const PointCloud& cloud) const {
    const GrowerConfig& cfg = config_;
    const int threads = cfg.threads > 0 ? cfg.threads : std::max(1, omp_get_num_procs());
    GrowResult result;
    GrowStats& st = result.stats;
    const std::size_t n_in = cloud.points.size();
    st.points_in = n_in;
    auto report = [&](std::string_view stage, double f) {
        if (cfg.progress) cfg.progress(stage, f);
    };

    // --- Stage 1: the cube index over valid points inside the crop.
    auto t0 = Clock::now();
    std::vector<std::uint8_t> include;
    if (cfg.crop.active()) {
        include.assign(n_in, 1);
        const Vec3d center = cfg.crop.center   ? *cfg.crop.center
                             : cfg.viewpoint   ? *cfg.viewpoint
                             : cloud.viewpoint ? *cloud.viewpoint
                                               : Vec3d(-cloud.offset);
        const double r2 = cfg.crop.radius ? *cfg.crop.radius * *cfg.crop.radius : 0.0;
        for (std::size_t i = 0; i < n_in; ++i) {
            const Vec3f& pf = cloud.points[i];
            if (!is_finite(pf)) continue;
            const Vec3d p = pf.cast<double>();
            const bool inside = (!cfg.crop.box || cfg.crop.box->contains(p)) &&
                                (!cfg.crop.radius || (p - center).squaredNorm() <= r2);
            if (!inside) {
                include[i] = 0;
                ++st.cropped_points;
            }
        }
    }
    const CubeIndex index(cloud.points, cfg.mu, include, threads);
    release(include);
    const std::size_t n = index.size();
    st.valid_points = n;
    st.invalid_points = n_in - n - st.cropped_points;
    st.seconds.index = seconds_since(t0);
    report("index", 1.0);

    // --- Stage 2: growing, slab by slab, even colour then odd.
    t0 = Clock::now();
    const int reach = static_cast<int>(std::ceil(cfg.max_radius() / index.cube_size()));
    const std::size_t target = std::clamp<std::size_t>(n / 256, 4096, 65536);
    const std::vector<Slab> slabs = partition_slabs(index, 2 * reach, target);
    BulkVector<std::int32_t> labels(n, -1);
    // Where each slab's surfaces lie: thread t's scratch.grown[begin, end).
    struct GrownSpan {
        std::size_t thread = 0, begin = 0, end = 0;
    };
    std::vector<GrownSpan> grown(slabs.size());
    std::vector<SlabCounters> counters(slabs.size());
    std::vector<Scratch> scratch(static_cast<std::size_t>(threads));
    // About one surface per 30 points in scans at the paper's mu; a buffer that fills up doubles.
    // Kept under 2 MiB for small clouds, where a huge page would mostly stay empty.
    for (Scratch& sc : scratch) sc.grown.reserve(n / (32 * scratch.size()) + 64);
    const GrowContext ctx{index, cfg, labels};
    std::atomic<std::size_t> done{0};
    for (int colour = 0; colour < 2; ++colour) {
        for_each_slab_of_colour(index, slabs, colour, threads, [&](std::size_t s, int t) {
            Scratch& sc = scratch[static_cast<std::size_t>(t)];
            const std::size_t begin = sc.grown.size();
            grow_slab(ctx, slabs[s], s, sc, sc.grown, counters[s]);
            grown[s] = {static_cast<std::size_t>(t), begin, sc.grown.size()};
            const std::size_t d = ++done;
            if (t == 0) report("grow", double(d) / double(slabs.size()));
        });
    }
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
    // pooling below, which is where small clouds reach their peak.
    for (Scratch& sc : scratch) {
        release(sc.grown);
        release(sc.order);
        release(sc.table);
    }
    // Every label left after growing is the home of a kept surface (undone homes reset theirs):
    // relabel through a home-to-surface table, read only at those homes. Allocated after the
    // thread buffers are freed, so that it does not add to the peak.
    BulkVector<std::int32_t> sid_of_home(n);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t k = 0; k < all.size(); ++k)
        sid_of_home[all[k].home] = static_cast<std::int32_t>(k);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        if (labels[i] >= 0) labels[i] = sid_of_home[static_cast<std::size_t>(labels[i])];
    }
    release(sid_of_home);
    const std::size_t surface_count = all.size();
    std::vector<std::uint32_t> home_of(surface_count);  // sorted index of each surface's home
    reserve_bulk(result.surfaces, surface_count);
    result.surfaces.resize(surface_count);
    std::vector<double> tolerance(surface_count);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t k = 0; k < surface_count; ++k) {
        const GrownSurface& g = all[k];
        home_of[k] = g.home;
        Surface& s = result.surfaces[k];
        s.home = index.world_point(g.home);
        s.centroid = s.home + g.fit.centroid;
        s.normal = g.fit.normal;
        s.eigenvalues = g.fit.eigenvalues;
        s.radius = g.radius;
        s.neighbours = g.neighbours;
        tolerance[k] = cfg.tolerance() * double(g.radius) / cfg.mu;
    }
    st.surfaces = surface_count;
    if (cfg.pool_angle_deg > 0 && surface_count > 0) {
        BulkVector<PoolablePatch> patches(surface_count);
#pragma omp parallel for num_threads(threads) schedule(static)
        for (std::size_t k = 0; k < surface_count; ++k) {
            const Surface& s = result.surfaces[k];
            patches[k] = {s.home, s.centroid, s.normal, s.eigenvalues[0], all[k].moments};
        }
        release(all);  // its moments are in the patches now: free them before pooling's own copy
        PoolingConfig pc;
        pc.radius = cfg.pool_radius > 0 ? cfg.pool_radius : 2 * cfg.mu;
        pc.max_angle = cfg.pool_angle_deg * M_PI / 180.0;
        pc.min_offset = cfg.mu / 10;
        pc.max_offset = cfg.mu / 2;
        pc.threads = threads;
        const std::vector<Vec3d> pooled = pool_normals(patches, pc);
        release(patches);
        for (std::size_t k = 0; k < surface_count; ++k) result.surfaces[k].normal = pooled[k];
        // A reported plane must hold its members: release any the refined plane no longer fits
        // (rare: points at the tolerance's edge); the leftover pass may re-attach them.
        std::uint64_t released = 0;
        std::vector<LocalPlane> planes = local_planes(index, result.surfaces, tolerance);
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
    release(all);
    st.seconds.grow = seconds_since(t0);
    for (const std::int32_t l : labels) st.registered_grown += l >= 0 ? 1 : 0;

    // --- Stage 3: attach leftovers to the best-fitting neighbouring surface.
    t0 = Clock::now();
    if (cfg.attach_leftovers && surface_count > 0) {
        std::vector<std::vector<std::pair<std::uint32_t, std::int32_t>>> attach(slabs.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
        for (std::size_t s = 0; s < slabs.size(); ++s) {
            attach_slab(index, cfg, slabs[s], labels, result.surfaces, tolerance,
                        scratch[static_cast<std::size_t>(omp_get_thread_num())], attach[s]);
        }
        for (const auto& list : attach)
            for (const auto& [i, sid] : list) labels[i] = sid;
    }
    st.seconds.attach = seconds_since(t0);
    report("attach", 1.0);

    // --- Stage 4: member statistics, orientation, labels in input order, range bands.
    t0 = Clock::now();
    const auto orig = index.original_indices();
    const Orientation orient = choose_orientation(cloud, cfg, index.bounds());
    st.orientation = orient.source;
    const bool per_scan = orient.source == OrientationSource::kScanOrigins;
    st.range_known = orient.source != OrientationSource::kUp;
    st.range_origin = orient.origin;
    // Labels in input order. Points not in the index (invalid, cropped) are marked first, so
    // that the range bands below can stream the input in its own order and skip them.
    constexpr std::int32_t kNotIndexed = -2;
    reserve_bulk(result.labels, n_in);
    result.labels.assign(n_in, kNotIndexed);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < n; ++i) result.labels[orig[i]] = labels[i];

    // Per-surface statistics, in the index's float frame: members, bounds, residual sum. Each
    // thread owns a range of surface ids and visits their members in point order, so every
    // residual sum is added up in the same order whatever the thread count.
    const std::vector<LocalPlane> planes = local_planes(index, result.surfaces, tolerance);
    std::vector<Vec3f> lo(surface_count, Vec3f::Constant(std::numeric_limits<float>::max()));
    std::vector<Vec3f> hi(surface_count, Vec3f::Constant(std::numeric_limits<float>::lowest()));
    std::vector<double> residual_sum(surface_count, 0.0);
#pragma omp parallel num_threads(threads)
    {
        const auto parts = static_cast<std::size_t>(omp_get_num_threads());
        const auto part = static_cast<std::size_t>(omp_get_thread_num());
        const auto from = static_cast<std::uint32_t>(surface_count * part / parts);
        const auto count = static_cast<std::uint32_t>(surface_count * (part + 1) / parts) - from;
        for (std::size_t i = 0; i < n; ++i) {
            // One unsigned compare: also false for the unregistered (-1).
            const std::uint32_t k = static_cast<std::uint32_t>(labels[i]) - from;
            if (k >= count) continue;
            const std::size_t s = from + k;
            const Vec3f p = index.local_point(static_cast<std::uint32_t>(i));
            ++result.surfaces[s].point_count;
            lo[s] = lo[s].cwiseMin(p);
            hi[s] = hi[s].cwiseMax(p);
            residual_sum[s] += static_cast<double>(planes[s].distance(p));
        }
    }

    // Registration by range band, over the input in its order (integer counts: any split of the
    // work gives the same totals); the not-indexed mark becomes the unregistered label.
    std::vector<RangeBand> bands;
    std::vector<Vec3f> origins;  // relative to the cloud's offset: one, or one per scan
    if (per_scan)
        for (const Vec3d& o : cloud.scan_origins) origins.push_back(o.cast<float>());
    else
        origins.push_back(orient.origin.cast<float>());
    const auto inv_band = static_cast<float>(1.0 / cfg.range_band);
    std::vector<std::vector<RangeBand>> thread_bands(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
    {
        std::vector<RangeBand>& mine = thread_bands[static_cast<std::size_t>(omp_get_thread_num())];
        if (st.range_known) mine.resize(kMaxRangeBands);
#pragma omp for schedule(static)
        for (std::size_t j = 0; j < n_in; ++j) {
            std::int32_t& l = result.labels[j];
            if (l == kNotIndexed) {
                l = -1;
                continue;
            }
            if (!st.range_known) continue;
            std::uint32_t o = 0;
            if (per_scan) {
                o = cloud.scan_index[j];
                if (o >= origins.size()) o = 0;
            }
            const float r = (cloud.points[j] - origins[o]).norm();
            const auto band =
                static_cast<std::size_t>(std::min(r * inv_band, float(kMaxRangeBands - 1)));
            ++mine[band].points;
            mine[band].registered += l >= 0 ? 1 : 0;
        }
    }
    if (st.range_known) {
        bands.resize(kMaxRangeBands);
        for (const auto& mine : thread_bands) {
            for (std::size_t b = 0; b < mine.size(); ++b) {
                bands[b].points += mine[b].points;
                bands[b].registered += mine[b].registered;
            }
        }
        while (!bands.empty() && bands.back().points == 0) bands.pop_back();
    }
    std::uint64_t registered = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : registered)
    for (std::size_t k = 0; k < surface_count; ++k) {
        Surface& s = result.surfaces[k];
        registered += s.point_count;
        if (s.point_count == 0) continue;
        s.mean_residual = residual_sum[k] / s.point_count;
        s.bounds.add(index.origin() + lo[k].cast<double>());
        s.bounds.add(index.origin() + hi[k].cast<double>());
    }
    st.registered = registered;
    st.noise_points = st.valid_points - st.registered;

    auto origin_of = [&](std::uint32_t sorted) -> Vec3d {
        if (per_scan) {
            const std::uint32_t scan = cloud.scan_index[orig[sorted]];
            if (scan < cloud.scan_origins.size()) return cloud.scan_origins[scan];
        }
        return orient.origin;
    };
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t k = 0; k < surface_count; ++k) {
        Surface& s = result.surfaces[k];
        const Vec3d towards = orient.source == OrientationSource::kUp
                                  ? Vec3d::UnitZ()
                                  : Vec3d(origin_of(home_of[k]) - s.home);
        if (s.normal.dot(towards) < 0) s.normal = -s.normal;
    }
    if (st.range_known) {
        for (std::size_t b = 0; b < bands.size(); ++b) {
            bands[b].from = double(b) * cfg.range_band;
            bands[b].to = double(b + 1) * cfg.range_band;
        }
        if (bands.size() == kMaxRangeBands)  // the last band is open-ended
            bands.back().to = std::numeric_limits<double>::infinity();
        st.range_bands = std::move(bands);
    }
    st.seconds.finish = seconds_since(t0);
    report("finish", 1.0);
    return result;
}

}  // namespace surfgrow
