#include "surfgrow/core/detail/neighbourhood_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "surfgrow/core/detail/neighbourhood.hpp"

namespace surfgrow::detail {

namespace {

// The normals of a neighbourhood's two halves may differ by at most this (degrees).
constexpr double kSplitAngleDeg = 20.0;
// A neighbourhood that fails eq. (2) is given a larger ball only while its thickness is that of
// the noise (at most this many sigmas): noise-limited far surfaces, not edges or steps.
constexpr double kGrowSigmas = 1.5;
// A ball judged within its layers widens its tolerance by its farthest layer's offset, up to this
// many sigmas of the layer offsets measured at its range (the leftover pass's budget for a
// layer, taken along the ray): layers farther apart than any scan's offset are more likely two
// surfaces than one. Taken along the normal, as that pass takes it, the budget left the pipes'
// fused worst bands 0.1-0.5 points lower on 8 of 22 draws: a cylinder's layers also lie apart by
// its curvature.
constexpr double kLayerSpreadSigmas = 4.0;

/// The disk test's last look at an accepted neighbourhood, in one pass over its inliers (the
/// points within its tolerance of its plane). Whether its two halves, split across each in-plane
/// principal axis at the centroid, lie in one plane: an edge or a depth edge's mixed pixels seen
/// at a small scale can look as thin as noise (an L of two short arms fitted by its diagonal), but
/// its halves are the two arms. Halves that are lines or hold fewer than 3 points say nothing.
/// Where they agree and some points are not inliers, the plane is refitted on the inliers, so
/// that the few points of a neighbouring face an edge patch holds no longer tilt it.
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
    // The inliers' moments about home, from their sums in the plane's frame. Where every point of
    // the ball is an inlier (98 % of the accepted balls on a scan) the fit already is theirs, and
    // more precise: its sums are of double offsets, the frame's of float projections.
    const double cnt = f.all[0];
    if (cnt >= ctx.config.min_pts && cnt < nb.moments.n) {
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

/// A fused cloud's ball is a stack of its scans' layers: each scan sees a surface a little off
/// the others along its rays (its range bias there, its pose error), and across a sparse ball
/// those offsets outweigh the noise. Fits the plane within the layers: the scatter of each scan's
/// points about their own mean, summed, so that the offsets between layers drop out, through the
/// centroid of all the points; `spread` is the farthest layer's offset from that plane (the mean
/// of a scan with at least 3 points there). False where the ball holds fewer than two scans.
bool fit_within_layers(const GrowContext& ctx, const Vec3f& h, const Neighbourhood& nb,
                       PlaneFit& out, double& spread) {
    // Per scan, reset after each ball for the scans it touched only (a cloud may fuse hundreds).
    thread_local std::vector<Moments> per_scan;
    thread_local std::vector<std::uint32_t> touched;
    if (per_scan.size() < ctx.sight.origins.size()) per_scan.resize(ctx.sight.origins.size());
    touched.clear();
    const auto r = static_cast<float>(nb.radius);
    for_each_in_runs_within(ctx.index, nb.runs, h, r * r, [&](std::uint32_t j) {
        const std::uint32_t s = ctx.sight.scan_of(j);
        if (s >= ctx.sight.origins.size()) return;
        if (per_scan[s].n == 0) touched.push_back(s);
        per_scan[s].add((ctx.index.local_point(j) - h).cast<double>());
    });
    // In scan order: the same sums for any order the points came in.
    std::sort(touched.begin(), touched.end());
    Moments within;  // about the origin of the summed scatter: only its covariance is used
    thread_local std::vector<Vec3d> means;  // of the scans with at least 3 points
    means.clear();
    for (const std::uint32_t s : touched) {
        Moments& m = per_scan[s];
        within.n += m.n;
        within.sum_sq += m.sum_sq - m.sum * m.sum.transpose() / m.n;
        if (m.n >= 3) means.push_back(m.sum / m.n);
        m = Moments{};
    }
    if (touched.size() < 2 || within.n != nb.moments.n) return false;
    out = fit_plane(within);
    out.centroid = nb.moments.sum / nb.moments.n;
    spread = 0;
    for (const Vec3d& mean : means)
        spread = std::max(spread, std::abs(out.normal.dot(mean - out.centroid)));
    return true;
}

}  // namespace

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
            // In a fused cloud, a ball thicker than growing allows is judged first within its
            // scans' layers, by the same tests: an edge, a step or a corner is as thick within
            // each layer, layers offset along their rays are not. Where that is a plane, the
            // ball takes the layers' normal, and a tolerance that spans its layers: the noise's,
            // plus the farthest layer's offset within the layer budget (with the noise's alone
            // its plane lay between the layers, and a layer that far off lost its farther half,
            // home and all: the far floor of the channel's fused scans on some draws).
            PlaneFit layered;
            double spread = 0;
            if (disk && ctx.sight.fused() && rough[0] > grow_var &&
                fit_within_layers(ctx, h, nb, layered, spread) &&
                layered.eigenvalues[0] <= max_var &&
                judge_plane(cfg.plane_test, test, layered.eigenvalues, layered.normal, nb.radius,
                            sight) == PlaneVerdict::kPlane) {
                nb.fit = layered;
                nb.verdict = PlaneVerdict::kPlane;
                nb.tolerance = tolerance_of(ctx, nb);
                if (cfg.tolerance() <= 0 && ctx.layers.known() && nb.range > 0)
                    nb.tolerance = std::min(
                        nb.tolerance +
                            std::min(spread, kLayerSpreadSigmas * ctx.layers.sigma(nb.range)),
                        nb.radius);
                if (!check_and_refit(ctx, home, h, nb)) nb.verdict = PlaneVerdict::kKinked;
                return nb;
            }
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

}  // namespace surfgrow::detail
