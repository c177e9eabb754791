#include "surfgrow/scanner/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/moments.hpp"
#include "surfgrow/core/plane_fit.hpp"
#include "surfgrow/core/random.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/scanner/range_filter.hpp"
#include "surfgrow/scanner/tilting_scanner.hpp"

namespace surfgrow::scanner {

namespace {

[[noreturn]] void invalid(const std::string& m) {
    throw Error(ErrorCode::kInvalidParameter, "calibrate: " + m);
}

std::string mm(double metres) {  // "25.5 mm"
    return num(std::round(metres * 1e4) / 10) + " mm";
}

// One filtered reading, with what places it: its scan's pose, its tilt and pan, the offset's
// in-plane part.
struct Reading {
    std::size_t scan;
    const Pose* pose;
    double tilt_rad;
    Vec3d beam;    // unit, laser frame
    Vec3d offset;  // the scan's optical offset with z = 0
    double range_m;
};

// The ray's world point for offset height h, zero z (radians) and its range scaled by `scale`.
Vec3d place(const Reading& r, double h, double zero, double scale = 1.0) {
    const double t = r.tilt_rad + zero;
    const Vec3d l = r.offset + Vec3d(0, 0, h) + scale * r.range_m * r.beam;
    // Ry(-t), as TiltingScanner: a positive tilt turns x toward +z.
    const Vec3d s(std::cos(t) * l.x() - std::sin(t) * l.z(), l.y(),
                  std::sin(t) * l.x() + std::cos(t) * l.z());
    return *r.pose * s;
}

Plane fit(const std::vector<Vec3d>& pts) {
    Moments m;
    const Vec3d ref = pts.front();
    for (const Vec3d& p : pts) m.add(p - ref);
    const PlaneFit f = fit_plane(m);
    return Plane::through(ref + f.centroid, f.normal);
}

// Signed distances of the rays' points to their own best plane, for (h, zero): the residual of
// variable projection (the plane is solved for inside).
// `scaled` scan's ranges (if any) are scaled by `scale`.
std::vector<double> residuals(const std::vector<Reading>& rays, double h, double zero,
                              Plane* plane = nullptr, std::size_t scaled = SIZE_MAX,
                              double scale = 1.0) {
    std::vector<Vec3d> pts(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
        pts[i] = place(rays[i], h, zero, rays[i].scan == scaled ? scale : 1.0);
    const Plane p = fit(pts);
    if (plane) *plane = p;
    std::vector<double> r(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) r[i] = p.signed_distance(pts[i]);
    return r;
}

// d(residual)/d(h, zero) of each point by central differences; the zero's column is 0 when it
// is not solved for.
std::vector<Eigen::Vector2d> jacobian(const std::vector<Reading>& rays, double h, double zero,
                                      bool with_zero) {
    constexpr double dh = 1e-4, dz = 1e-5;
    const std::vector<double> hp = residuals(rays, h + dh, zero),
                              hm = residuals(rays, h - dh, zero);
    std::vector<double> zp, zm;
    if (with_zero) zp = residuals(rays, h, zero + dz), zm = residuals(rays, h, zero - dz);
    std::vector<Eigen::Vector2d> j(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
        j[i] = Eigen::Vector2d((hp[i] - hm[i]) / (2 * dh),
                               with_zero ? (zp[i] - zm[i]) / (2 * dz) : 0.0);
    return j;
}

double rms(const std::vector<double>& r) {
    double s = 0;
    for (const double v : r) s += v * v;
    return r.empty() ? 0.0 : std::sqrt(s / static_cast<double>(r.size()));
}

// The plane with most points within `tol`: RANSAC over a spread of at most 4000 points.
Plane largest_plane(const std::vector<Vec3d>& pts, double tol, std::uint64_t seed) {
    SplitMix64 rng(seed);
    const std::size_t step = std::max<std::size_t>(1, pts.size() / 4000);
    std::vector<const Vec3d*> sample;
    for (std::size_t i = 0; i < pts.size(); i += step) sample.push_back(&pts[i]);
    Plane best;
    std::size_t best_count = 0;
    const auto n = static_cast<std::uint32_t>(sample.size());
    for (int iter = 0; iter < 400; ++iter) {
        const Vec3d& a = *sample[rng.below(n)];
        const Vec3d& b = *sample[rng.below(n)];
        const Vec3d& c = *sample[rng.below(n)];
        const Vec3d normal = (b - a).cross(c - a);
        if (normal.norm() < 1e-9) continue;
        const Plane p = Plane::through(a, normal.normalized());
        std::size_t count = 0;
        for (const Vec3d* q : sample) count += std::abs(p.signed_distance(*q)) < tol;
        if (count > best_count) best_count = count, best = p;
    }
    return best;
}

// How far the points bow away from their plane: the RMS of the quadric in the plane's own
// coordinates (u, v) that fits their signed distances best. The offset bends a plane the way it
// bends with the tilt and is solved for; what is left and smooth is the surface's own shape.
double bow(const std::vector<Vec3d>& pts, const std::vector<double>& dist, const Plane& plane) {
    const Vec3d n = plane.normal;
    const Vec3d u = n.unitOrthogonal(), v = n.cross(u);
    Vec3d mean = Vec3d::Zero();
    for (const Vec3d& p : pts) mean += p;
    mean /= static_cast<double>(pts.size());
    double extent = 0;
    for (const Vec3d& p : pts) extent = std::max(extent, (p - mean).norm());
    if (!(extent > 0)) return 0.0;
    using Vec6 = Eigen::Matrix<double, 6, 1>;
    auto basis = [&](const Vec3d& p) {  // scaled to about 1 for a well-conditioned fit
        const double a = (p - mean).dot(u) / extent, b = (p - mean).dot(v) / extent;
        Vec6 f;
        f << 1, a, b, a * a, a * b, b * b;
        return f;
    };
    Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
    Vec6 atb = Vec6::Zero();
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const Vec6 f = basis(pts[i]);
        ata += f * f.transpose();
        atb += f * dist[i];
    }
    const Vec6 c = ata.ldlt().solve(atb);
    double s = 0;
    for (const Vec3d& p : pts) {
        const double q = basis(p).dot(c);
        s += q * q;
    }
    return std::sqrt(s / static_cast<double>(pts.size()));
}

}  // namespace

CalibrationResult calibrate(std::span<const RawScan> scans, const CalibrationOptions& o) {
    if (scans.empty()) invalid("no scans");
    if (!(o.inlier_m > 0) || o.max_points < 500) invalid("inlier distance or point count");
    // The readings, filtered (eq. 1), as rays.
    std::vector<Reading> all;
    std::vector<Vec3d> offsets;
    for (std::size_t k = 0; k < scans.size(); ++k) {
        const RawScan& s = scans[k];
        s.validate();
        if (s.partial())
            invalid(
                cat({"scan ", std::to_string(k), " is partial: take the calibration scans again"}));
        const TiltingScanner geo(s.spec, s.tilt_read_deg);
        const RangeFilter filter(s.spec.readings_per_ray, o.trim_q, s.spec.laser.min_range_mm,
                                 s.spec.laser.max_range_mm);
        Vec3d offset = s.spec.optical_offset_m;
        offset.z() = 0;
        for (int i = 0; i < geo.tilt_count(); ++i)
            for (int j = 0; j < geo.step_count(); ++j) {
                const double mm = filter(s.ray_readings(geo.ray_index(i, j)));
                if (!std::isnan(mm))
                    all.push_back(
                        {k, &s.pose, geo.tilt_rad(i), geo.beam_in_laser(j), offset, mm * 1e-3});
            }
    }
    const double h0 = scans.front().spec.optical_offset_m.z();
    std::vector<Vec3d> pts(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) pts[i] = place(all[i], h0, 0.0);
    if (pts.size() < 500)
        invalid(cat({"only ", std::to_string(pts.size()), " points in the scans"}));

    // The surface: the largest plane, refit on its points, then an even spread of them.
    Plane plane = largest_plane(pts, o.inlier_m, o.seed);
    std::vector<Reading> on;
    const auto select = [&](const Plane& p, double tol) {
        std::vector<std::size_t> idx;
        for (std::size_t i = 0; i < pts.size(); ++i)
            if (std::abs(p.signed_distance(pts[i])) < tol) idx.push_back(i);
        const std::size_t step = std::max<std::size_t>(1, idx.size() / o.max_points + 1);
        on.clear();
        for (std::size_t i = 0; i < idx.size(); i += step) on.push_back(all[idx[i]]);
    };
    select(plane, o.inlier_m);
    if (on.size() < 500)
        invalid(cat({"only ", std::to_string(on.size()),
                     " points on the largest plane: scan a large flat surface"}));

    CalibrationResult out;
    // Gauss-Newton on (h, zero), the Jacobian by central differences. The zero is solved for
    // only where the scans can tell it.
    bool with_zero = scans.size() > 1;
    double h = h0, zero = 0.0;
    Eigen::Matrix2d normal_matrix = Eigen::Matrix2d::Identity();
    double sigma2 = 0;
    for (int pass = 0; pass < 2; ++pass) {
        for (int iter = 0; iter < 30; ++iter) {
            const std::vector<double> r = residuals(on, h, zero);
            const std::vector<Eigen::Vector2d> j = jacobian(on, h, zero, with_zero);
            Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
            Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
            for (std::size_t i = 0; i < r.size(); ++i) {
                jtj += j[i] * j[i].transpose();
                jtr += j[i] * r[i];
            }
            if (!with_zero) jtj(1, 1) = 1;
            normal_matrix = jtj;
            const Eigen::Vector2d step = -jtj.ldlt().solve(jtr);
            h += step[0];
            zero += with_zero ? step[1] : 0.0;
            if (std::abs(step[0]) < 1e-7 && std::abs(step[1]) < 1e-8) break;
        }
        const std::vector<double> r = residuals(on, h, zero, &plane);
        sigma2 = rms(r) * rms(r) * static_cast<double>(r.size()) /
                 static_cast<double>(r.size() - (with_zero ? 5 : 4));
        const Eigen::Matrix2d cov = sigma2 * normal_matrix.inverse();
        // A zero the scans hardly see (its noise alone puts it half a degree out) is not
        // reported.
        if (with_zero && std::sqrt(cov(1, 1)) > deg_to_rad(0.5)) {
            with_zero = false;
            zero = 0;
            pass = -1;  // solve again for the offset alone
            continue;
        }
        // Again on the points of the surface as now placed: within 4 sigma of it. Not after
        // the last pass: its figures belong to the points it solved on.
        if (pass == 1) break;
        for (std::size_t i = 0; i < all.size(); ++i) pts[i] = place(all[i], h, zero);
        select(plane, std::max(4 * std::sqrt(sigma2), 0.002));
    }
    const std::vector<double> r = residuals(on, h, zero, &plane);
    Eigen::Matrix2d cov = sigma2 * normal_matrix.inverse();
    // The sensor's systematic error: each scan's ranges off by a factor (1 + c_k), c_k of sigma
    // range_scale_sigma, shifts its surface a little; with few scans that, not the noise,
    // limits the estimate. Propagated: d(h, zero) = -(J'J)^-1 J' (dr/dc_k) c_k for each scan.
    if (o.range_scale_sigma > 0) {
        const Eigen::Matrix2d inv = normal_matrix.inverse();
        const std::vector<Eigen::Vector2d> j = jacobian(on, h, zero, with_zero);  // once
        for (std::size_t k = 0; k < scans.size(); ++k) {
            constexpr double dc = 1e-4;
            const std::vector<double> up = residuals(on, h, zero, nullptr, k, 1 + dc);
            const std::vector<double> down = residuals(on, h, zero, nullptr, k, 1 - dc);
            Eigen::Vector2d jtc = Eigen::Vector2d::Zero();
            for (std::size_t i = 0; i < r.size(); ++i) jtc += j[i] * (up[i] - down[i]) / (2 * dc);
            const Eigen::Vector2d a = inv * jtc * o.range_scale_sigma;
            cov += a * a.transpose();
        }
    }
    out.calibration = {h, with_zero ? rad_to_deg(zero) : 0.0};
    out.offset_sigma_m = std::sqrt(cov(0, 0));
    // A surface seen over few tilt rows, or edge-on, hardly bends with the offset: such an
    // estimate would silently misplace every later scan converted with it.
    if (!(out.offset_sigma_m <= o.max_offset_sigma_m))
        invalid(cat({"the largest plane in the scans cannot tell the optical offset (", mm(h),
                     " +- ", mm(out.offset_sigma_m),
                     "): scan a floor or wall that fills many tilt rows, facing the scanner"}));
    // A curved surface (a tank, a hull) flattened by a wrong offset: refused, it would bend
    // every later scan the other way.
    std::vector<Vec3d> placed(on.size());
    for (std::size_t i = 0; i < on.size(); ++i) placed[i] = place(on[i], h, zero);
    out.bow_m = bow(placed, r, plane);
    if (!(out.bow_m <= o.max_bow_m))
        invalid(cat({"the largest plane in the scans is not flat: its points bow ", mm(out.bow_m),
                     " rms away from it once calibrated (at most ", mm(o.max_bow_m),
                     "): scan a flat floor, wall or plate"}));
    out.zero_estimated = with_zero;
    out.zero_sigma_deg = with_zero ? rad_to_deg(std::sqrt(cov(1, 1))) : 0.0;
    out.plane = plane;
    out.points = on.size();
    out.rms_before_m = rms(residuals(on, h0, 0.0));  // the same points, as recorded
    out.rms_after_m = rms(r);
    return out;
}

void apply_calibration(RawScan& scan, const Calibration& c) {
    scan.spec.optical_offset_m.z() = c.optical_offset_m;
    if (scan.tilt_read_deg.empty()) {
        scan.spec.tilt.first_deg += c.tilt_zero_deg;
    } else {
        for (double& deg : scan.tilt_read_deg) deg += c.tilt_zero_deg;
    }
}

}  // namespace surfgrow::scanner
