#include "surfgrow/core/plane_pooling.hpp"

#include <algorithm>
#include <cmath>

#include "surfgrow/core/cube_index.hpp"

namespace surfgrow {

namespace {

// The moments of a set about `from`, re-expressed about `to` (d' = d + (from - to)).
Moments shifted(const Moments& m, const Vec3d& from, const Vec3d& to) {
    const Vec3d t = from - to;
    Moments out;
    out.n = m.n;
    out.sum = m.sum + m.n * t;
    out.sum_sq = m.sum_sq + m.sum * t.transpose() + t * m.sum.transpose() + m.n * t * t.transpose();
    return out;
}

}  // namespace

std::vector<Vec3d> pool_normals(std::span<const PoolablePatch> patches, const PoolingConfig& cfg) {
    std::vector<Vec3d> out(patches.size());
    if (patches.empty()) return out;
    std::vector<Vec3f> homes(patches.size());
    for (std::size_t k = 0; k < patches.size(); ++k) homes[k] = patches[k].home.cast<float>();
    const CubeIndex index(homes, cfg.radius, {}, cfg.threads);
    const auto orig = index.original_indices();
    const double cos_max = std::cos(cfg.max_angle);

#pragma omp parallel for num_threads(std::max(1, cfg.threads)) schedule(dynamic, 256)
    for (std::size_t k = 0; k < patches.size(); ++k) {
        const PoolablePatch& a = patches[k];
        Moments pooled = a.moments;
        index.for_each_within(a.home, cfg.radius, [&](std::uint32_t s) {
            const std::size_t j = orig[s];
            if (j == k) return;
            const PoolablePatch& b = patches[j];
            if (std::abs(a.normal.dot(b.normal)) < cos_max) return;
            const double sigma = std::sqrt(std::max(a.lambda_min, b.lambda_min));
            const double offset = std::clamp(3.0 * sigma, cfg.min_offset, cfg.max_offset);
            const Vec3d d = b.centroid - a.centroid;
            if (std::abs(a.normal.dot(d)) > offset || std::abs(b.normal.dot(d)) > offset) return;
            const Moments m = shifted(b.moments, b.home, a.home);
            pooled.n += m.n;
            pooled.sum += m.sum;
            pooled.sum_sq += m.sum_sq;
        });
        Vec3d n = fit_plane(pooled).normal;
        if (n.dot(a.normal) < 0) n = -n;
        out[k] = n;
    }
    return out;
}

}  // namespace surfgrow
