#include "surfgrow/planes/detail/region_plane.hpp"

#include <algorithm>
#include <cmath>

#include "surfgrow/planes/boundary_polygon.hpp"
#include "surfgrow/planes/detail/region_fit.hpp"
#include "surfgrow/planes/plane_raster.hpp"

namespace surfgrow::detail {

namespace {

constexpr double kDeg = M_PI / 180.0;
// A face's plane is refitted on the member points within this many robust sigmas (1.4826 x the
// median distance) of the previous fit, at most this many times.
constexpr double kInlierSigmas = 3.0;
constexpr int kRefitPasses = 5;
// Sigma is taken over at most this many points evenly spread through the members (a few per
// cent of noise in a threshold at 3 sigma, for a fraction of the cost on big faces).
constexpr std::size_t kSigmaSample = 8192;
// A region's plane is refitted on at most this many of its member points, taken evenly through
// them: on a face of 500,000 points the plane moves by thousandths of a degree, and the passes
// cost an eighth.
constexpr std::size_t kFitSample = std::size_t{1} << 16;

// Calls f(point) for every member point of the region, patch by patch, from the member lists
// in place.
template <class F>
void for_each_point(const RegionInput& in, F&& f) {
    for (const std::uint32_t s : in.patches)
        for (const Vec3f& x : in.members.points_of(s)) f(x.cast<double>());
}

// The plane of the points within k robust sigma of (normal, centroid), as moments: points of
// a neighbouring face that some patch near the edge registered within its tolerance tilt a
// least-squares fit of all members; the inliers' fit does without them.
CentredMoments inlier_moments(std::span<const Vec3d> points, const Vec3d& normal,
                              const Vec3d& centroid, double k, double floor_scale,
                              std::vector<double>& scratch) {
    scratch.clear();
    const std::size_t stride = points.size() / kSigmaSample + 1;
    for (std::size_t i = 0; i < points.size(); i += stride)
        scratch.push_back(std::abs(normal.dot(points[i] - centroid)));
    const auto mid = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
    std::nth_element(scratch.begin(), mid, scratch.end());
    const double sigma = scratch.empty() ? 0.0 : 1.4826 * *mid;
    // Points exactly on a plane still scatter by the float coordinates' rounding: keep them.
    const double limit = std::max(k * sigma, 1e-6 * floor_scale);
    Moments about_centroid;
    for (const Vec3d& p : points) {
        const Vec3d d = p - centroid;
        if (std::abs(normal.dot(d)) > limit) continue;
        about_centroid.add(d);
    }
    if (about_centroid.n < 3) return {};
    return CentredMoments::of(about_centroid, centroid);
}

// The in-plane axis of largest spread, with a deterministic sign.
Vec3d principal_axis(const Vec3d& n, const Mat3d& scatter) {
    const Vec3d e1 = n.unitOrthogonal();
    const Vec3d e2 = n.cross(e1);
    const double a = e1.dot(scatter * e1), b = e2.dot(scatter * e2), c = e1.dot(scatter * e2);
    const double phi = 0.5 * std::atan2(2 * c, a - b);
    Vec3d u = (std::cos(phi) * e1 + std::sin(phi) * e2).normalized();
    Eigen::Index k = 0;
    u.cwiseAbs().maxCoeff(&k);
    return u[k] < 0 ? Vec3d(-u) : u;
}

// The gap closing of a region's boundary: the configured one, else the larger of the resolution
// and 1.5 x its median point spacing, from its patches' neighbourhoods.
double closing_radius_of(const RegionInput& in, const BoundPlaneConfig& cfg) {
    if (cfg.closing_radius > 0) return cfg.closing_radius;
    std::vector<double> spacing;
    for (const std::uint32_t s : in.patches) {
        const Surface& f = in.surfaces[s];
        if (f.neighbours > 0)
            spacing.push_back(std::sqrt(M_PI * f.radius * f.radius / double(f.neighbours)));
    }
    return std::max(cfg.resolution, 1.5 * median_of(std::move(spacing)));
}

Aabb bounds_of(const RegionInput& in) {  // of the member points: their patches' boxes
    Aabb box;
    for (const std::uint32_t s : in.patches)
        if (!in.boxes[s].empty()) {
            box.add(in.boxes[s].min);
            box.add(in.boxes[s].max);
        }
    return box;
}

// A region's plane: its normal (facing as most of its patches do), centroid and whether its
// points define it, from inlier refits over at most kFitSample of its member points, taken
// evenly through them (all of them in smaller regions).
struct RegionFit {
    Vec3d normal = Vec3d::UnitZ();
    Vec3d centroid = Vec3d::Zero();
    bool degenerate = true;
};

RegionFit fit_plane(const RegionInput& in) {
    const CentredMoments& all = in.all;
    const auto n = static_cast<std::size_t>(all.n);
    const std::size_t stride = n / kFitSample + 1;
    std::vector<Vec3d> points;  // the sample, contiguous: every pass below streams it
    points.reserve(n / stride + 1);
    std::size_t at = 0, next = 0;
    for (const std::uint32_t s : in.patches) {
        const auto part = in.members.points_of(s);
        for (; next < at + part.size(); next += stride)
            points.push_back(part[next - at].cast<double>());
        at += part.size();
    }
    Fit fit = region_fit(all, in.judge);
    CentredMoments m = all;
    if (!fit.degenerate) {
        // Until the inliers stop changing (two or three passes on the test scenes).
        const double spread = std::sqrt(all.scatter.trace() / all.n);
        std::vector<double> scratch;
        for (int pass = 0; pass < kRefitPasses; ++pass) {
            const CentredMoments inliers =
                inlier_moments(points, fit.normal, m.mean, kInlierSigmas, spread, scratch);
            const Fit f = region_fit(inliers, in.judge);
            if (inliers.n < 3 || f.degenerate) break;
            const bool same = inliers.n == m.n;
            m = inliers;
            fit = f;
            if (same) break;
        }
    }
    RegionFit r;
    r.centroid = m.mean;
    r.degenerate = fit.degenerate;
    Vec3d normal = fit.normal;
    if (fit.degenerate) {  // the patches' own normals, sign-aligned and point-weighted
        Vec3d sum = Vec3d::Zero();
        for (const std::uint32_t s : in.patches)
            add_normal(sum, in.surfaces[s].normal, in.moments[s].n);
        normal = sum.norm() > 0 ? Vec3d(sum.normalized()) : in.surfaces[in.patches[0]].normal;
    }
    // Orientation: the majority of the member patches' (sensor-facing) normals; a tie goes
    // to the point-weighted vote, then to the first patch.
    long votes = 0;
    double weight = 0;
    for (const std::uint32_t s : in.patches) {
        const double d = in.surfaces[s].normal.dot(normal);
        votes += d >= 0 ? 1 : -1;
        weight += (d >= 0 ? 1 : -1) * in.moments[s].n;
    }
    const bool flip =
        votes != 0 ? votes < 0
                   : (weight != 0 ? weight < 0 : in.surfaces[in.patches[0]].normal.dot(normal) < 0);
    r.normal = flip ? Vec3d(-normal) : normal;
    return r;
}

// The plane of a region but its frame and boundary: what fit_region and extend_region share.
BoundPlane plane_of(const RegionInput& in, const RegionFit& f, const BoundPlaneConfig& cfg) {
    BoundPlane plane;
    plane.patches.assign(in.patches.begin(), in.patches.end());
    plane.point_count = static_cast<std::uint64_t>(in.all.n);
    plane.centroid = f.centroid;
    plane.degenerate = f.degenerate;
    plane.normal = f.normal;
    plane.rms = std::sqrt(std::max(0.0, in.all.mean_square_distance(plane.normal, f.centroid)));
    plane.bounds = bounds_of(in);
    plane.closing_radius = closing_radius_of(in, cfg);
    return plane;
}

// The plane's polygons and area from its closed raster, whose coordinates (a, b) are those of
// the point origin + a u + b v (another frame of about the same plane: the plane's when it was
// last fitted anew).
void trace(BoundPlane& plane, const PlaneRaster& closed, const Vec3d& origin, const Vec3d& u,
           const Vec3d& v, const BoundPlaneConfig& cfg) {
    plane.polygons =
        trace_boundaries(closed, cfg.simplify_tolerance, 2 * closed.cell * closed.cell);
    if (origin != plane.centroid || u != plane.u_axis || v != plane.v_axis) {
        const Vec2d shift = plane.to_plane(origin);
        const Vec2d au(u.dot(plane.u_axis), u.dot(plane.v_axis));
        const Vec2d av(v.dot(plane.u_axis), v.dot(plane.v_axis));
        for (PolygonWithHoles& poly : plane.polygons) {
            for (Vec2d& q : poly.outer) q = shift + q.x() * au + q.y() * av;
            for (Ring& hole : poly.holes)
                for (Vec2d& q : hole) q = shift + q.x() * au + q.y() * av;
        }
    }
    plane.area = 0;
    for (const PolygonWithHoles& poly : plane.polygons) plane.area += polygon_area(poly);
}

// The cell of a point on a lattice through `base` (as mark_points rounds it).
std::pair<long, long> cell_of(const Vec2d& p, const Vec2d& base, double cell) {
    return {std::lround((p.x() - base.x()) / cell), std::lround((p.y() - base.y()) / cell)};
}

// The counts of the points' cells on the lattice of `marks` (mark_points' raster of them).
CellCounts count_cells(const PlaneRaster& marks, std::span<const Vec2d> flat) {
    CellCounts c{marks.origin, marks.cell, 0, 0, marks.width, marks.height, {}};
    c.count.assign(marks.cells.size(), 0);
    for (const Vec2d& p : flat) {
        const auto [x, y] = cell_of(p, c.base, c.cell);
        ++c.count[static_cast<std::size_t>(y * c.width + x)];
    }
    return c;
}

// Takes the points `gone` out of the counts and adds `added`, widening them on their lattice
// where the cells with points, and the border a closing by `closing_radius` needs beyond them,
// fall outside. False when a point to take out is not counted, or the raster would grow beyond
// kMaxRasterCells: the counts are then not to be used.
bool recount(CellCounts& c, std::span<const Vec2d> gone, std::span<const Vec2d> added,
             double closing_radius) {
    const double far = double(kMaxRasterCells);
    for (const Vec2d& p : gone) {
        const auto [x, y] = cell_of(p, c.base, c.cell);
        if (x < c.x0 || y < c.y0 || x >= c.x0 + c.width || y >= c.y0 + c.height) return false;
        std::uint32_t& n = c.count[static_cast<std::size_t>((y - c.y0) * c.width + (x - c.x0))];
        if (n == 0) return false;
        --n;
    }
    // The box of the cells with points, old and new.
    long bx0 = c.x0 + c.width, by0 = c.y0 + c.height, bx1 = c.x0 - 1, by1 = c.y0 - 1;
    for (long y = 0; y < c.height; ++y)
        for (long x = 0; x < c.width; ++x)
            if (c.count[static_cast<std::size_t>(y * c.width + x)]) {
                bx0 = std::min(bx0, c.x0 + x), bx1 = std::max(bx1, c.x0 + x);
                by0 = std::min(by0, c.y0 + y), by1 = std::max(by1, c.y0 + y);
            }
    std::vector<std::pair<long, long>> at;
    at.reserve(added.size());
    for (const Vec2d& p : added) {
        const double fx = (p.x() - c.base.x()) / c.cell, fy = (p.y() - c.base.y()) / c.cell;
        if (!(std::abs(fx) < far && std::abs(fy) < far)) return false;  // far off
        const auto [x, y] = cell_of(p, c.base, c.cell);
        at.emplace_back(x, y);
        bx0 = std::min(bx0, x), bx1 = std::max(bx1, x), by0 = std::min(by0, y),
        by1 = std::max(by1, y);
    }
    if (bx1 < bx0) return false;  // no points left
    const long m = static_cast<long>(std::ceil(closing_radius / c.cell)) + 2;
    const long x0 = std::min(c.x0, bx0 - m), y0 = std::min(c.y0, by0 - m);
    const long x1 = std::max(c.x0 + c.width - 1, bx1 + m);
    const long y1 = std::max(c.y0 + c.height - 1, by1 + m);
    const long w = x1 - x0 + 1, h = y1 - y0 + 1;
    if (double(w) * double(h) > far) return false;
    if (x0 != c.x0 || y0 != c.y0 || w != c.width || h != c.height) {
        std::vector<std::uint32_t> count(static_cast<std::size_t>(w * h), 0);
        for (long y = 0; y < c.height; ++y)
            std::copy_n(c.count.begin() + y * c.width, c.width,
                        count.begin() + (y + c.y0 - y0) * w + (c.x0 - x0));
        c.count = std::move(count);
        c.x0 = x0, c.y0 = y0, c.width = w, c.height = h;
    }
    for (const auto& [x, y] : at)
        ++c.count[static_cast<std::size_t>((y - c.y0) * c.width + (x - c.x0))];
    return true;
}

// The occupied cells of the counts, as a raster.
PlaneRaster occupancy(const CellCounts& c) {
    PlaneRaster r;
    r.cell = c.cell;
    r.origin = c.base + c.cell * Vec2d(double(c.x0), double(c.y0));
    r.width = static_cast<int>(c.width);
    r.height = static_cast<int>(c.height);
    std::vector<std::uint8_t> cells(c.count.size(), 0);
    for (std::size_t i = 0; i < c.count.size(); ++i) cells[i] = c.count[i] > 0 ? 1 : 0;
    r.cells = std::move(cells);
    return r;
}

}  // namespace

double median_of(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

namespace {

// fit_region with the plane fitted: frame, bounds and boundary on a raster of every point.
BoundPlane rasterised(const RegionInput& in, const RegionFit& f, const BoundPlaneConfig& cfg,
                      RegionState* state) {
    BoundPlane plane = plane_of(in, f, cfg);
    plane.u_axis = principal_axis(plane.normal, in.all.scatter);
    plane.v_axis = plane.normal.cross(plane.u_axis);
    std::vector<Vec2d> flat;
    flat.reserve(plane.point_count);
    for_each_point(in, [&](const Vec3d& p) { flat.push_back(plane.to_plane(p)); });
    PlaneRaster raster = mark_points(flat, cfg.resolution, plane.closing_radius);
    if (state) {
        *state = {};
        if (!plane.degenerate)
            *state = {plane.normal, plane.u_axis, plane.v_axis, plane.centroid,
                      count_cells(raster, flat)};
    }
    close_gaps(raster, plane.closing_radius);
    trace(plane, raster, plane.centroid, plane.u_axis, plane.v_axis, cfg);
    return plane;
}

// Whether extend_region may extend `was` before its plane is fitted.
bool extendable(const RegionInput& in, const FittedRegion& was) {
    return !was.state.cells.count.empty() && in.all.n <= 2 * was.moments.n;
}

// extend_region with the plane fitted.
std::optional<BoundPlane> traced_on_counts(const RegionInput& in, const RegionFit& f,
                                           const FittedRegion& was,
                                           std::span<const std::uint32_t> known,
                                           const BoundPlaneConfig& cfg, RegionState& state) {
    const RegionState& old = was.state;
    if (f.degenerate || f.normal.dot(old.normal) < std::cos(kExtendDeg * kDeg)) return std::nullopt;
    // The points that left (the members the last call saw of was's patches that are another
    // region's now) and those that joined (the members past those of was's patches, all of
    // any other patch), in the frame of the last fit anew.
    const std::vector<std::uint32_t>& before = was.plane.patches;
    std::vector<Vec2d> gone, added;
    const auto flatten = [&](std::span<const Vec3f> points, std::vector<Vec2d>& flat) {
        for (const Vec3f& x : points) {
            const Vec3d d = x.cast<double>() - old.anchor;
            flat.emplace_back(d.dot(old.u_axis), d.dot(old.v_axis));
        }
    };
    for (const std::uint32_t s : before)
        if (!std::binary_search(in.patches.begin(), in.patches.end(), s))
            flatten(in.members.points_of(s).first(known[s]), gone);
    for (const std::uint32_t s : in.patches) {
        const bool seen = std::binary_search(before.begin(), before.end(), s);
        flatten(in.members.points_of(s).subspan(seen ? known[s] : 0), added);
    }
    BoundPlane plane = plane_of(in, f, cfg);
    RegionState next = old;
    if (!recount(next.cells, gone, added, plane.closing_radius)) return std::nullopt;
    // The axes turned with the normal (the least rotation from the old normal to the new).
    const Vec3d axis = old.normal.cross(plane.normal);
    const double c = old.normal.dot(plane.normal);
    plane.u_axis =
        (old.u_axis * c + axis.cross(old.u_axis) + axis * (axis.dot(old.u_axis) / (1 + c)))
            .normalized();
    plane.u_axis = (plane.u_axis - plane.normal * plane.normal.dot(plane.u_axis)).normalized();
    plane.v_axis = plane.normal.cross(plane.u_axis);
    PlaneRaster closed = occupancy(next.cells);
    close_gaps(closed, plane.closing_radius);
    trace(plane, closed, old.anchor, old.u_axis, old.v_axis, cfg);
    state = std::move(next);
    return plane;
}

}  // namespace

BoundPlane fit_region(const RegionInput& in, const BoundPlaneConfig& cfg, RegionState* state) {
    return rasterised(in, fit_plane(in), cfg, state);
}

std::optional<BoundPlane> extend_region(const RegionInput& in, const FittedRegion& was,
                                        std::span<const std::uint32_t> known,
                                        const BoundPlaneConfig& cfg, RegionState& state) {
    if (!extendable(in, was)) return std::nullopt;
    return traced_on_counts(in, fit_plane(in), was, known, cfg, state);
}

BoundPlane region_plane(const RegionInput& in, const FittedRegion* was,
                        std::span<const std::uint32_t> known, const BoundPlaneConfig& cfg,
                        RegionState* state) {
    const RegionFit f = fit_plane(in);
    if (was && state && extendable(in, *was))
        if (std::optional<BoundPlane> plane = traced_on_counts(in, f, *was, known, cfg, *state))
            return std::move(*plane);
    return rasterised(in, f, cfg, state);
}

}  // namespace surfgrow::detail
