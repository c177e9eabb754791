#include "surfgrow/core/plane_pooling.hpp"

#include <algorithm>
#include <cmath>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/bulk_allocator.hpp"

namespace surfgrow {

using detail::BulkVector;
using detail::reserve_bulk;

namespace {

// What the inner loop tests of a patch, in the pooling index's sorted order (contiguous reads):
// one cache line. Its sums, read only for the coplanar ones, lie apart (SumsOf).
struct alignas(64) Candidate {
    Vec3d normal;
    Vec3d centroid;  // index-local
    double sigma;    // sqrt(lambda_min)
    double n;        // its points
};

// The rest of a candidate's moments, about the index origin, so pooling is a plain sum.
struct SumsOf {
    Vec3d sum;
    Mat3d sum_sq;
};

}  // namespace

std::vector<Vec3d> pool_normals(std::span<const PoolablePatch> patches, const PoolingConfig& cfg) {
    std::vector<std::uint8_t> lone;
    return pool_normals(patches, cfg, lone, {});
}

std::vector<Vec3d> pool_normals(std::span<const PoolablePatch> patches, const PoolingConfig& cfg,
                                std::vector<std::uint8_t>& lone, const LoneRule& rule) {
    const bool marks = rule.min_neighbours > 0;
    lone.assign(marks ? patches.size() : 0, 0);
    std::vector<Vec3d> out;
    reserve_bulk(out, patches.size());
    out.resize(patches.size());
    if (patches.empty()) return out;
    std::vector<Vec3f> homes(patches.size());
    for (std::size_t k = 0; k < patches.size(); ++k) homes[k] = patches[k].home.cast<float>();
    // Cubes of the pooling radius over the home points: every candidate is in the 27 around.
    const CubeIndex index(homes, cfg.radius, {}, cfg.threads);
    const auto orig = index.original_indices();
    std::vector<CubeIndex::Range> table;
    index.neighbour_table(0, index.cube_count(), table);
    // Moments about the index origin: at metre scale in double the sums lose ~1e-14 m^2, far
    // below a patch's spread, and pooling needs no per-pair shift.
    BulkVector<Candidate> cand(index.size());
    BulkVector<SumsOf> sums(index.size());
#pragma omp parallel for num_threads(std::max(1, cfg.threads)) schedule(static)
    for (std::size_t s = 0; s < index.size(); ++s) {
        const PoolablePatch& p = patches[orig[s]];
        const Moments m = moments_about(p.moments, p.home, index.origin());
        cand[s] = {p.normal, p.centroid - index.origin(), std::sqrt(std::max(p.lambda_min, 0.0)),
                   m.n};
        sums[s] = {m.sum, m.sum_sq};
    }
    const double cos_max = std::cos(cfg.max_angle);
    const auto r2 = static_cast<float>(cfg.radius * cfg.radius);

#pragma omp parallel for num_threads(std::max(1, cfg.threads)) schedule(dynamic, 64)
    for (std::size_t c = 0; c < index.cube_count(); ++c) {
        for (std::uint32_t s = index.cube_begin(c); s < index.cube_end(c); ++s) {
            const Candidate& a = cand[s];
            const Vec3f q = index.local_point(s);
            Moments pooled{a.n, sums[s].sum, sums[s].sum_sq};
            int near = 0, coplanar = 0;
            // Points behind this patch's plane here, and behind the planes across it.
            auto in_plane = static_cast<double>(a.n);
            double elsewhere = 0;
            for (int r = 0; r < 9; ++r) {
                const CubeIndex::Range run = table[9 * c + static_cast<std::size_t>(r)];
                for (std::uint32_t t = run.begin; t < run.end; ++t) {
                    if (t == s || (index.local_point(t) - q).squaredNorm() > r2) continue;
                    const Candidate& b = cand[t];
                    ++near;
                    if (std::abs(a.normal.dot(b.normal)) < cos_max) {
                        elsewhere += static_cast<double>(b.n);
                        continue;
                    }
                    const double offset = std::clamp(3.0 * std::max(a.sigma, b.sigma),
                                                     cfg.min_offset, cfg.max_offset);
                    const Vec3d d = b.centroid - a.centroid;
                    // Parallel but offset (another layer, the far side of a plate): neither.
                    if (std::abs(a.normal.dot(d)) > offset || std::abs(b.normal.dot(d)) > offset)
                        continue;
                    ++coplanar;
                    in_plane += static_cast<double>(b.n);
                    pooled.n += b.n;
                    pooled.sum += sums[t].sum;
                    pooled.sum_sq += sums[t].sum_sq;
                }
            }
            Vec3d n = fit_plane(pooled).normal;
            if (n.dot(a.normal) < 0) n = -n;
            out[orig[s]] = n;
            if (marks && near >= rule.min_neighbours &&
                (coplanar == 0 || in_plane < rule.minority_share * elsewhere))
                lone[orig[s]] = 1;
        }
    }
    return out;
}

}  // namespace surfgrow
