// The study behind the adaptive-radius and alpha defaults (docs/algorithm.md): registered share and
// per-point normal error against the simulator's true normals, on simulated I-beam channel scans.
// Run: build/bench/accuracy_study
#include <algorithm>
#include <cstdio>
#include <vector>

#include "simulated_scans.hpp"
#include "surfgrow/core/surface_grower.hpp"

using namespace surfgrow;

namespace {

double quantile(std::vector<double> v, double f) {
    if (v.empty()) return 0;
    const auto k = static_cast<std::size_t>(f * double(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

// Registered share and normal error of the truth-labelled points within `radius` of their scan.
void report(const char* label, const PointCloud& cloud, const scanner::Scene& scene,
            const GrowResult& r, double radius) {
    std::vector<double> err;
    std::size_t n = 0, registered = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (cloud.labels[i] < 0 || !is_finite(cloud.points[i])) continue;
        const Vec3d p = cloud.points[i].cast<double>();
        if ((p - cloud.scan_origins[cloud.scan_index[i]]).norm() > radius) continue;
        ++n;
        if (r.labels[i] < 0) continue;
        ++registered;
        const Vec3d truth = scene.normal_at(cloud.labels[i], p);
        err.push_back(
            axis_angle_between(r.surfaces[static_cast<std::size_t>(r.labels[i])].normal, truth) *
            180 / M_PI);
    }
    std::printf(
        "  %-28s within %.1f m: %7.2f %% registered, normal error median %.2f p95 %.2f deg, %llu "
        "surfaces\n",
        label, radius, 100.0 * double(registered) / double(std::max<std::size_t>(n, 1)),
        quantile(err, 0.5), quantile(err, 0.95), static_cast<unsigned long long>(r.stats.surfaces));
}

}  // namespace

int main() {
    const scanner::SceneDescription desc = scanner::builtin_scene("ibeam-channel");
    const scanner::Scene scene(desc);
    for (int poses : {1, 4}) {
        const PointCloud cloud = bench::ibeam_channel_scan(poses);
        std::printf("ibeam-channel, %d scan(s), %zu points\n", poses, cloud.size());
        for (double factor : {1.0, 2.0, 4.0}) {
            GrowerConfig c;
            c.adaptive_factor = factor;
            const GrowResult r = grow_surfaces(cloud, c);
            char label[64];
            std::snprintf(label, sizeof label, "adaptive up to %.0f mu", factor);
            for (double radius : {1.0, 1.5, 3.0}) report(label, cloud, scene, r, radius);
        }
        for (double alpha : {2.0, 3.0, 4.0, 6.0}) {
            for (bool attach : {false, true}) {
                GrowerConfig c;
                c.alpha = alpha;
                c.attach_leftovers = attach;
                const GrowResult r = grow_surfaces(cloud, c);
                char label[64];
                std::snprintf(label, sizeof label, "alpha %.0f%s", alpha,
                              attach ? " + leftovers" : "");
                report(label, cloud, scene, r, 1.5);
            }
        }
        GrowerConfig c;
        c.pool_angle_deg = 0;
        report("no normal pooling", cloud, scene, grow_surfaces(cloud, c), 1.5);
    }
}
