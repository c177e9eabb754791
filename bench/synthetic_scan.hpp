// A scan-like cloud for kernel benchmarks: a tilting scanner's ray grid cast into a room with a
// beam in it. (The full simulator lives in surfgrow_scanner; this keeps the kernels' benchmarks
// free of it.)
#pragma once

#include <cmath>
#include <limits>
#include <random>

#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow::bench {

/// Distance along unit direction d from inside an axis-aligned box to its wall.
inline double exit_distance(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
    double t = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 1e-12) t = std::min(t, (hi[a] - o[a]) / d[a]);
        if (d[a] < -1e-12) t = std::min(t, (lo[a] - o[a]) / d[a]);
    }
    return t;
}

/// Entry distance into a box from outside, or infinity.
inline double entry_distance(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
    double t0 = 0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (o[a] < lo[a] || o[a] > hi[a]) return std::numeric_limits<double>::infinity();
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

/// `poses` scans of tilts x steps rays (the paper: 360 x 768), 2 mm range noise, fused.
inline PointCloud synthetic_scan(int poses, int tilts = 360, int steps = 768,
                                 std::uint64_t seed = 1) {
    PointCloud cloud;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.002);
    const Vec3d room_lo(-1.5, -1.2, -0.9), room_hi(1.5, 1.2, 1.1);
    const Vec3d beam_lo(-1.5, 0.4, 0.6), beam_hi(1.5, 0.7, 1.1);  // a box beam under the ceiling
    for (int p = 0; p < poses; ++p) {
        const Vec3d o(-0.6 + 0.4 * p, -0.3, 0.0);
        cloud.scan_origins.push_back(o);
        for (int t = 0; t < tilts; ++t) {
            const double tilt = (-60.0 + 120.0 * t / tilts) * M_PI / 180;
            for (int s = 0; s < steps; ++s) {
                const double pan = (-120.0 + 240.0 * s / steps) * M_PI / 180;
                const Vec3d d(std::cos(tilt) * std::cos(pan), std::cos(tilt) * std::sin(pan),
                              std::sin(tilt));
                double r = std::min(exit_distance(o, d, room_lo, room_hi),
                                    entry_distance(o, d, beam_lo, beam_hi));
                if (r < 0.02 || r > 4.0) continue;
                r += noise(rng);
                cloud.points.push_back((o + r * d).cast<float>());
                cloud.scan_index.push_back(static_cast<std::uint32_t>(p));
            }
        }
    }
    return cloud;
}

}  // namespace surfgrow::bench
