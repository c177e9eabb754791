#include "surfgrow/core/surface_grower.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <string_view>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/bulk_allocator.hpp"
#include "surfgrow/core/detail/neighbourhood.hpp"
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

constexpr std::size_t kMaxRangeBands = 1024;
// The frame origin counts as the sensor if it lies within this many box diagonals of the points.
constexpr double kFrameOriginReach = 10.0;
using Range = CubeIndex::Range;
// The noise profile: this many sample neighbourhoods, in range bands of this many mu, and no
// sigma below mu / kNoiseFloorPerMu (float coordinates and 1 mm range steps at mu = 12 mm).
constexpr std::size_t kNoiseSamples = 1536;
constexpr double kNoiseBandPerMu = 25.0;
constexpr double kNoiseFloorPerMu = 24.0;
// The normals of a neighbourhood's two halves may differ by at most this (degrees).
constexpr double kSplitAngleDeg = 20.0;
// A leftover beside surfaces that it does not fit looks for others up to this many mu away; the
// wider searches double their radius at most this many times (the adaptive radius's 64 mu).
constexpr double kMissRadiusPerMu = 2.0;
constexpr std::size_t kFarLevels = 7;
// A patch with at least this many patches around it, none of them in its plane, is dropped.
constexpr int kLoneNeighbours = 3;
// So is one whose plane holds less than this share of the points of the other planes around it:
// a depth edge's mixed pixels make a ramp one beam footprint wide between two faces, locally a
// plane, outweighed by the faces; a narrow real face is sampled across its width and keeps its
// weight. The study that chose a fifth: docs/algorithm.md.
constexpr double kMinorityShare = 0.2;
// Fused clouds: a leftover that lies in another scan's layer of a surface, as far from it as this
// many sigmas of the measured layer offsets, goes to that surface (attach_layer).
constexpr double kLayerSigmas = 3.0;
// ... if at least this many unregistered points of its own scan around it make that layer.
constexpr int kLayerMinPoints = 4;
// A scan's range bias moves its layer along the rays: by cos(incidence) of it along the normal,
// counted as at least this much (grazing layers are few and thin on the ground).
constexpr double kMinLayerCos = 0.25;
// The median of |x| for a zero-mean Gaussian x is this many sigmas.
constexpr double kMedianAbsPerSigma = 0.6745;
// A neighbourhood that fails eq. (2) is given a larger ball only while its thickness is that of
// the noise (at most this many sigmas): noise-limited far surfaces, not edges or steps.
constexpr double kGrowSigmas = 1.5;

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
    float tolerance = 0;  // registration tolerance
    std::uint32_t neighbours = 0;
    PlaneFit fit;     // centroid relative to the home point, local frame
    Moments moments;  // about the home point, for normal pooling
};

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

/// Per-thread scratch reused across slabs: no allocation per home point.
struct Scratch {
    BulkVector<GrownSurface> grown;  // every slab this thread grew, one after another
    std::vector<std::uint32_t> order;
    std::vector<Range> table;
    std::vector<Range> runs;
    std::array<std::vector<Range>, kFarLevels> far_runs;  // the leftover pass's wider searches
    std::vector<TakenPoint> taken;
};

/// Where the sensor stood for each point, in the index's local frame (kDisk's grazing test).
struct SensorSight {
    std::vector<Vec3f> origins;  // local; empty: unknown
    // The grazing test needs a sensor the cloud or the user names (scan origins, a viewpoint):
    // a frame origin is only a guess, and a map-frame cloud has it on its floor.
    bool named = false;
    std::span<const std::uint32_t> scan_index;  // input order; empty: origins[0] for all
    std::span<const std::uint32_t> original;    // sorted index -> input index

    /// Whether the points come from more than one scan (a fused cloud).
    [[nodiscard]] bool fused() const { return !scan_index.empty() && origins.size() > 1; }
    /// The scan of sorted point `i` (0 unless fused).
    [[nodiscard]] std::uint32_t scan_of(std::uint32_t i) const {
        return scan_index.empty() ? 0 : scan_index[original[i]];
    }
    /// Direction from the sensor to sorted point `i` at local position `p`; zero when unknown.
    [[nodiscard]] Vec3d towards(std::uint32_t i, const Vec3f& p) const {
        if (origins.empty()) return Vec3d::Zero();
        std::uint32_t o = 0;
        if (!scan_index.empty()) {
            o = scan_index[original[i]];
            if (o >= origins.size()) o = 0;
        }
        return (p - origins[o]).cast<double>();
    }
};

struct GrowContext {
    const CubeIndex& index;
    const GrowerConfig& config;
    std::span<std::int32_t> labels;  // sorted order; during growing: the home's sorted index
    std::span<float> distance;       // sorted order: a registered point's distance to its plane
    const SensorSight& sight;
    const NoiseProfile& noise;   // measured plane thickness by range (kDisk); may be unknown
    const NoiseProfile& layers;  // fused clouds: the scans' offsets from each other, by range
};

/// A home point's neighbourhood at the radius where the search stopped.
struct Neighbourhood {
    PlaneVerdict verdict = PlaneVerdict::kThick;
    double radius = 0;
    double range = -1;  // from the sensor; < 0: unknown
    Moments moments;
    PlaneFit fit;
    std::span<const Range> runs;  // the cube runs that cover the ball
    double tolerance = 0;         // registration tolerance (accepted neighbourhoods)
};

/// The registration tolerance of an accepted neighbourhood: the user's, per mu of radius; or a few
/// sigmas of the noise measured at its range (its own thickness while the noise is measured),
/// never less than the coordinates' rounding needs, never more than the radius.
double tolerance_of(const GrowContext& ctx, const Neighbourhood& nb) {
    const GrowerConfig& cfg = ctx.config;
    if (cfg.tolerance() > 0) return cfg.tolerance() * nb.radius / cfg.mu;
    const double sigma = ctx.noise.known() ? ctx.noise.sigma(std::max(nb.range, 0.0))
                                           : std::sqrt(nb.fit.eigenvalues[0]);
    return std::clamp(cfg.noise_sigmas * sigma, cfg.mu / 6, nb.radius);
}

/// The disk test's last look at an accepted neighbourhood, in one pass over its inliers (the
/// points within its tolerance of its plane). Whether its two halves, split across each in-plane
/// principal axis at the centroid, lie in one plane: an edge or a depth edge's mixed pixels seen
/// at a small scale can look as thin as noise (an L of two short arms fitted by its diagonal), but
/// its halves are the two arms. Halves that are lines or hold fewer than 3 points say nothing.
/// Where they agree, the plane is refitted on the inliers, so that the few points of a
/// neighbouring face an edge patch holds no longer tilt it.
bool check_and_refit(const GrowContext& ctx, std::uint32_t home, const Vec3f& h,
                     Neighbourhood& nb) {
    const Vec3d& n = nb.fit.normal;
    const Vec3d e1 = eigenvector_of(covariance(nb.moments), nb.fit.eigenvalues[1], n);
    const Vec3d u = (e1 - e1.dot(n) * n).normalized();
    const Vec3d v = n.cross(u);
    const Vec3d& c = nb.fit.centroid;
    const FrameSums f = gather_frame_sums(ctx.index, nb.runs, h, static_cast<float>(nb.radius),
                                          c.cast<float>(), u.cast<float>(), v.cast<float>(),
                                          n.cast<float>(), static_cast<float>(nb.tolerance));
    // The noise variance along the normal: measured, or the neighbourhood's own.
    const double noise_var = ctx.noise.known()
                                 ? std::pow(ctx.noise.sigma(std::max(nb.range, 0.0)), 2)
                                 : nb.fit.eigenvalues[0];
    // Each half's plane as a regression of r on (u, v): a 2x2 solve from its sums.
    for (int a = 0; a < 2; ++a) {
        Vec3d half_normal[2];
        double wander = 0;
        bool usable = true;
        for (int k = 0; k < 2 && usable; ++k) {
            const double sign = k == 0 ? 1.0 : -1.0;
            double m[9];  // 1, u, v, r, uu, uv, ur, vv, vr of this half
            for (int t = 0; t < 9; ++t) m[t] = 0.5 * (f.all[t] + sign * f.signed_by[a][t]);
            const double cnt = m[0];
            if (cnt < 3) {
                usable = false;
                break;
            }
            const double mu_ = m[1] / cnt, mv = m[2] / cnt, mr = m[3] / cnt;
            const double cuu = m[4] / cnt - mu_ * mu_, cuv = m[5] / cnt - mu_ * mv;
            const double cur = m[6] / cnt - mu_ * mr, cvv = m[7] / cnt - mv * mv;
            const double cvr = m[8] / cnt - mv * mr;
            const double det = cuu * cvv - cuv * cuv;
            if (!(det > 1e-12 * cuu * cvv) || !(std::min(cuu, cvv) > 0)) {
                usable = false;  // a line: its tilt across itself is undefined
                break;
            }
            const double gu = (cvv * cur - cuv * cvr) / det;
            const double gv = (cuu * cvr - cuv * cur) / det;
            half_normal[k] = (n - gu * u - gv * v).normalized();
            // A half's normal wanders by about sigma / sqrt(n * spread) radians.
            wander += noise_var * std::max(cuu, cvv) / (cnt * det);
        }
        if (!usable) continue;
        // The limit: kSplitAngleDeg, or three wanders combined, whichever is larger.
        const double limit = std::max(kSplitAngleDeg * M_PI / 180.0, 3 * std::sqrt(wander));
        if (limit >= M_PI / 2) continue;
        if (std::abs(half_normal[0].dot(half_normal[1])) < std::cos(limit)) return false;
    }
    // The inliers' moments about home, from their sums in the plane's frame.
    const double cnt = f.all[0];
    if (cnt >= ctx.config.min_pts) {
        Mat3d r;
        r.col(0) = u;
        r.col(1) = v;
        r.col(2) = n;
        const Vec3d sq(f.all[1], f.all[2], f.all[3]);
        Mat3d qq;
        qq << f.all[4], f.all[5], f.all[6], f.all[5], f.all[7], f.all[8], f.all[6], f.all[8],
            f.all[9];
        Moments inliers;
        inliers.n = cnt;
        const Vec3d rs = r * sq;
        inliers.sum = cnt * c + rs;
        inliers.sum_sq = cnt * c * c.transpose() + c * rs.transpose() + rs * c.transpose() +
                         r * qq * r.transpose();
        // The refit must pass the same test (it reports these eigenvalues).
        const PlaneFit refit = fit_plane(inliers);
        if (judge_plane(ctx.config.plane_test, ctx.config.disk_test(), refit.eigenvalues,
                        refit.normal, nb.radius,
                        ctx.sight.named ? ctx.sight.towards(home, h) : Vec3d::Zero()) ==
            PlaneVerdict::kPlane) {
            nb.fit = refit;
            nb.moments = inliers;
        }
    }
    return true;
}

/// Fits the neighbourhood of sorted point `home` in cube `cube`, whose 27 cubes are `runs27`.
/// kPaper: eq. (2) at mu, or at the adaptive radius if mu holds fewer than min_pts points. kDisk:
/// the radius doubles while the neighbourhood fails the relative tests (too few points, eq. (2),
/// spread, grazing), and the search stops at once where the neighbourhood is thicker than
/// `thickness_sigmas` noise sigmas at its range (an edge, a step, a corner: growing cannot help).
/// Without a known noise profile that limit is not applied (the profile's own sampling).
Neighbourhood fit_neighbourhood(const GrowContext& ctx, std::uint32_t home, const Vec3f& h,
                                std::uint32_t cube, std::span<const Range> runs27,
                                std::vector<Range>& wide_runs) {
    const CubeIndex& index = ctx.index;
    const GrowerConfig& cfg = ctx.config;
    const bool disk = cfg.plane_test == PlaneTest::kDisk;
    const Vec3d towards = ctx.sight.towards(home, h);
    const Vec3d sight = disk && ctx.sight.named ? towards : Vec3d::Zero();  // for the grazing test
    Neighbourhood nb;
    nb.range = ctx.sight.origins.empty() ? -1.0 : towards.norm();
    // Thickness limits: to be a plane at all, and to be worth a larger ball after failing
    // eq. (2) (noise thins out as the ball grows; an edge or a step does not).
    double max_var = std::numeric_limits<double>::infinity(), grow_var = max_var;
    if (disk && ctx.noise.known()) {
        const double sigma = ctx.noise.sigma(std::max(nb.range, 0.0));
        max_var = cfg.thickness_sigmas * cfg.thickness_sigmas * sigma * sigma;
        grow_var = kGrowSigmas * kGrowSigmas * sigma * sigma;
    }
    const DiskTest test = cfg.disk_test();
    nb.radius = cfg.mu;
    nb.runs = runs27;
    nb.moments = gather_moments(index, nb.runs, h, static_cast<float>(cfg.mu));
    for (;;) {
        const Moments& m = nb.moments;
        if (m.n >= cfg.min_pts) {
            // Most edge and clutter neighbourhoods fail eq. (2) plainly: the cubic's eigenvalues
            // say so at a third of the full solve's cost.
            const Vec3d rough = rough_eigenvalues(covariance(m));
            if (clearly_not_planar(rough, cfg.alpha)) {
                nb.verdict = PlaneVerdict::kThick;
                // Only a full disk as thick as the noise thins out in a larger ball; a thicker
                // one is an edge or a step, a partial one a boundary or a corner.
                if (!disk || rough[0] > grow_var ||
                    rough[1] < cfg.min_spread * disk_variance(nb.radius))
                    return nb;
            } else {
                nb.fit = fit_plane(m);
                nb.verdict = judge_plane(cfg.plane_test, test, nb.fit.eigenvalues, nb.fit.normal,
                                         nb.radius, sight);
                if (nb.fit.eigenvalues[0] > max_var) {
                    nb.verdict = PlaneVerdict::kThick;
                    return nb;
                }
                if (nb.verdict == PlaneVerdict::kPlane) {
                    nb.tolerance = tolerance_of(ctx, nb);
                    if (disk && !check_and_refit(ctx, home, h, nb))
                        nb.verdict = PlaneVerdict::kKinked;
                }
                if (nb.verdict == PlaneVerdict::kPlane || nb.verdict == PlaneVerdict::kKinked)
                    return nb;
                if (nb.verdict == PlaneVerdict::kThick && nb.fit.eigenvalues[0] > grow_var)
                    return nb;
            }
            // The paper's test keeps the radius of any neighbourhood with min_pts points.
            if (!disk) return nb;
        }
        if (nb.radius >= cfg.max_radius()) return nb;
        // Adaptive radius: double it while the support is too thin, up to the maximum.
        nb.radius = std::min(2.0 * nb.radius, cfg.max_radius());
        wide_runs.clear();
        index.column_ranges(index.cube_coords(cube),
                            static_cast<int>(std::ceil(nb.radius / index.cube_size())), wide_runs);
        nb.runs = wide_runs;
        nb.moments = gather_moments(index, nb.runs, h, static_cast<float>(nb.radius));
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

    /// Whether each point's range from a sensor is known (not when normals merely face +z).
    [[nodiscard]] bool range_known() const { return source != OrientationSource::kUp; }
};

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
    reserve_bulk(surfaces, count);
    surfaces.resize(count);
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

/// Stage 4a: each surface's members (count, bounds, mean residual, largest distance), in the
/// index's float frame. Each thread owns a range of surface ids and visits their members in point
/// order, so every residual sum is added up in the same order whatever the thread count. Returns
/// the points registered.
std::uint64_t member_statistics(const CubeIndex& index, std::span<const std::int32_t> labels,
                                std::span<const double> tolerance, int threads,
                                std::vector<Surface>& surfaces) {
    const std::size_t surface_count = surfaces.size();
    const std::size_t n = labels.size();
    const std::vector<LocalPlane> planes = local_planes(index, surfaces, tolerance);
    std::vector<Vec3f> lo(surface_count, Vec3f::Constant(std::numeric_limits<float>::max()));
    std::vector<Vec3f> hi(surface_count, Vec3f::Constant(std::numeric_limits<float>::lowest()));
    std::vector<double> residual_sum(surface_count, 0.0);
    std::vector<float> max_distance(surface_count, 0.0f);
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
            ++surfaces[s].point_count;
            lo[s] = lo[s].cwiseMin(p);
            hi[s] = hi[s].cwiseMax(p);
            const float d = planes[s].distance(p);
            residual_sum[s] += static_cast<double>(d);
            max_distance[s] = std::max(max_distance[s], d);
        }
    }
    std::uint64_t registered = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : registered)
    for (std::size_t k = 0; k < surface_count; ++k) {
        Surface& s = surfaces[k];
        registered += s.point_count;
        if (s.point_count == 0) continue;
        s.mean_residual = residual_sum[k] / s.point_count;
        // The tolerance reported bounds every member, those the leftover pass gave it included.
        s.tolerance = std::max(s.tolerance, static_cast<double>(max_distance[k]));
        s.bounds.add(index.origin() + lo[k].cast<double>());
        s.bounds.add(index.origin() + hi[k].cast<double>());
    }
    return registered;
}

/// Marks the input points that are not in the index (invalid, cropped) in result labels.
constexpr std::int32_t kNotIndexed = -2;

/// Stage 4b: registration by range band, over the input in its order (integer counts: any split
/// of the work gives the same totals); the not-indexed mark becomes the unregistered label.
std::vector<RangeBand> range_bands(const CloudView& cloud, const Orientation& orient,
                                   double band_width, int threads,
                                   std::span<std::int32_t> input_labels) {
    const bool range_known = orient.range_known();
    const bool per_scan = orient.source == OrientationSource::kScanOrigins;
    std::vector<Vec3f> origins;  // relative to the cloud's offset: one, or one per scan
    if (per_scan)
        for (const Vec3d& o : cloud.scan_origins) origins.push_back(o.cast<float>());
    else
        origins.push_back(orient.origin.cast<float>());
    const auto inv_band = static_cast<float>(1.0 / band_width);
    const std::size_t n_in = input_labels.size();
    std::vector<std::vector<RangeBand>> thread_bands(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
    {
        std::vector<RangeBand>& mine = thread_bands[static_cast<std::size_t>(omp_get_thread_num())];
        if (range_known) mine.resize(kMaxRangeBands);
#pragma omp for schedule(static)
        for (std::size_t j = 0; j < n_in; ++j) {
            std::int32_t& l = input_labels[j];
            if (l == kNotIndexed) {
                l = -1;
                continue;
            }
            if (!range_known) continue;
            std::uint32_t o = 0;
            if (per_scan) {
                o = cloud.scan_index[j];
                if (o >= origins.size()) o = 0;
            }
            const float r = (cloud.points[j] - origins[o]).norm();
            // As std::min, but a NaN (a range from an infinitely far origin) goes to the last
            // band instead of an undefined cast.
            const float x = r * inv_band;
            const auto band =
                x < float(kMaxRangeBands - 1) ? static_cast<std::size_t>(x) : kMaxRangeBands - 1;
            ++mine[band].points;
            mine[band].registered += l >= 0 ? 1 : 0;
        }
    }
    std::vector<RangeBand> bands;
    if (!range_known) return bands;
    bands.resize(kMaxRangeBands);
    for (const auto& mine : thread_bands) {
        for (std::size_t b = 0; b < mine.size(); ++b) {
            bands[b].points += mine[b].points;
            bands[b].registered += mine[b].registered;
        }
    }
    while (!bands.empty() && bands.back().points == 0) bands.pop_back();
    for (std::size_t b = 0; b < bands.size(); ++b) {
        bands[b].from = double(b) * band_width;
        bands[b].to = double(b + 1) * band_width;
    }
    if (bands.size() == kMaxRangeBands)  // the last band is open-ended
        bands.back().to = std::numeric_limits<double>::infinity();
    return bands;
}

/// Stage 4c: every normal faces its home point's sensor (or +z when none is known). A guessed
/// frame origin that sees a surface edge-on (its plane passes near the origin: a map-frame
/// cloud's floor) says nothing about its side: that surface faces +z instead.
/// Returns the members of those surfaces.
std::uint64_t orient_normals(const CloudView& cloud, const Orientation& orient,
                             std::span<const std::uint32_t> original,
                             std::span<const std::uint32_t> home_of, double max_incidence_deg,
                             int threads, std::vector<Surface>& surfaces) {
    std::uint64_t edge_on = 0;
    // Edge-on: the origin lies within the grazing angle of the fitted plane (through the
    // centroid) or within its tolerance, where noise alone decides the side.
    const bool guessed = orient.source == OrientationSource::kFrameOrigin;
    const double cos_grazing = std::cos(max_incidence_deg * (std::numbers::pi / 180.0));
    auto seen_edge_on = [&](const Surface& s) {
        const Vec3d from_plane = orient.origin - s.centroid;
        return std::abs(s.normal.dot(from_plane)) <
               std::max(cos_grazing * from_plane.norm(), s.tolerance);
    };
    const bool per_scan = orient.source == OrientationSource::kScanOrigins;
    auto origin_of = [&](std::uint32_t sorted) -> Vec3d {
        if (per_scan) {
            const std::uint32_t scan = cloud.scan_index[original[sorted]];
            if (scan < cloud.scan_origins.size()) return cloud.scan_origins[scan];
        }
        return orient.origin;
    };
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : edge_on)
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
        Surface& s = surfaces[k];
        Vec3d towards = orient.source == OrientationSource::kUp
                            ? Vec3d::UnitZ()
                            : Vec3d(origin_of(home_of[k]) - s.home);
        if (guessed && seen_edge_on(s)) {
            towards = Vec3d::UnitZ();
            edge_on += s.point_count;
        }
        if (s.normal.dot(towards) < 0) s.normal = -s.normal;
    }
    return edge_on;
}

/// Stage 4d: best-fit registration can take every member of a surface; such surfaces are dropped
/// (ids stay in home order) and the labels renumbered. Returns how many were dropped.
std::uint64_t drop_empty_surfaces(int threads, std::vector<Surface>& surfaces,
                                  std::span<std::int32_t> input_labels) {
    const std::size_t count = surfaces.size();
    const auto kept = static_cast<std::size_t>(std::count_if(
        surfaces.begin(), surfaces.end(), [](const Surface& s) { return s.point_count > 0; }));
    if (kept == count) return 0;
    std::vector<std::int32_t> new_id(count, -1);
    std::size_t next = 0;
    for (std::size_t k = 0; k < count; ++k) {
        if (surfaces[k].point_count == 0) continue;
        new_id[k] = static_cast<std::int32_t>(next);
        surfaces[next++] = surfaces[k];
    }
    surfaces.resize(kept);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t j = 0; j < input_labels.size(); ++j) {
        std::int32_t& l = input_labels[j];
        if (l >= 0) l = new_id[static_cast<std::size_t>(l)];
    }
    return count - kept;
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
    std::vector<std::uint32_t> home_of(surface_count);  // sorted index of each surface's home
    std::vector<double> tolerance(surface_count);
    surfaces_of(all, index, threads, result.surfaces, home_of, tolerance);
    if (cfg.pool_angle_deg > 0 && surface_count > 0)
        refine_normals(cfg, index, threads, all, result.surfaces, tolerance, labels, st);
    release(all);
    st.seconds.grow = stage.lap();
    for (const std::int32_t l : labels) st.registered_grown += l >= 0 ? 1 : 0;

    // --- Stage 3: attach leftovers to the best-fitting neighbouring surface.
    if (cfg.attach_leftovers && surface_count > 0)
        attach_leftovers(ctx, slabs, result.surfaces, tolerance, threads, scratch, labels);
    st.seconds.attach = stage.lap();
    report("attach", 1.0);

    // --- Stage 4: member statistics, labels in input order, range bands, orientation.
    release(distance);
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
