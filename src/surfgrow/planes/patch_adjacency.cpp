#include "surfgrow/planes/patch_adjacency.hpp"

#include <omp.h>

#include <algorithm>
#include <array>

#include "surfgrow/core/detail/bulk_allocator.hpp"
#include "surfgrow/core/detail/neighbourhood.hpp"

namespace surfgrow {

// The neighbourhood kernels and bulk arrays of the core, for the index over seam points.
using namespace detail;

std::vector<std::uint64_t> merged_unique(
    std::initializer_list<const std::vector<std::vector<std::uint64_t>>*> sources) {
    std::vector<std::uint64_t> all;
    for (const auto* parts : sources)
        for (const auto& v : *parts) all.insert(all.end(), v.begin(), v.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
}

// Adjacency of patches: member points within `reach` of each other, or home points within the
// sum of the radii. Sorted, unique pairs (a < b). The search runs in parallel over batches of
// cubes; each batch keeps its pairs sorted and unique, and the final sort makes the result
// independent of the thread count.
std::vector<std::pair<std::uint32_t, std::uint32_t>> adjacent_patch_pairs(
    std::span<const Vec3f> points, std::span<const std::int32_t> labels,
    std::span<const Surface> surfaces, const std::vector<std::uint8_t>& used, double reach,
    int threads) {
    std::vector<std::uint8_t> include(points.size(), 0);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < points.size(); ++i)
        include[i] = labels[i] >= 0 && used[static_cast<std::size_t>(labels[i])] ? 1 : 0;
    const CubeIndex index(points, 2 * reach, include, threads);
    release(include);
    std::vector<std::int32_t> label(index.size() + CubeIndex::kPadding, -1);  // SIMD-readable
    const auto original = index.original_indices();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < index.size(); ++i) label[i] = labels[original[i]];
    const float r2 = static_cast<float>(reach * reach);
    constexpr std::size_t kBatch = 4096;  // cubes per neighbour-table sweep: bounded memory
    const std::size_t batches = (index.cube_count() + kBatch - 1) / kBatch;
    std::vector<std::vector<std::uint64_t>> found(batches);
#pragma omp parallel num_threads(threads)
    {
        std::vector<CubeIndex::Range> table;
#pragma omp for schedule(dynamic, 1)
        for (std::size_t b = 0; b < batches; ++b) {
            const std::size_t c0 = b * kBatch, c1 = std::min(index.cube_count(), c0 + kBatch);
            index.neighbour_table(c0, c1, table);
            std::vector<std::uint64_t>& out = found[b];
            for (std::size_t c = c0; c < c1; ++c) {
                const std::size_t cube_first = out.size();
                const CubeIndex::Range* runs = &table[9 * (c - c0)];
                for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
                    std::array<CubeIndex::Range, 9> after;  // each pair once: j > i
                    for (std::size_t k = 0; k < 9; ++k)
                        after[k] = {std::max(runs[k].begin, i + 1), std::max(runs[k].end, i + 1)};
                    const auto li = static_cast<std::uint32_t>(label[i]);
                    for_each_other_in_runs_within(
                        index, after, index.local_point(i), r2, label.data(), label[i],
                        [&](std::uint32_t j) {
                            const std::uint64_t kj =
                                pair_key(li, static_cast<std::uint32_t>(label[j]));
                            if (out.size() == cube_first || out.back() != kj) out.push_back(kj);
                        });
                }
                // Unique per cube (short lists to sort), then per batch, in parallel: the final
                // serial sort then has far fewer keys.
                const auto first = out.begin() + static_cast<std::ptrdiff_t>(cube_first);
                std::sort(first, out.end());
                out.erase(std::unique(first, out.end()), out.end());
            }
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        }
    }
    // Home points within the sum of the radii.
    std::vector<Vec3f> homes(surfaces.size());
    double max_radius = 0;
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        homes[s] = surfaces[s].home.cast<float>();
        if (used[s]) max_radius = std::max(max_radius, surfaces[s].radius);
    }
    std::vector<std::vector<std::uint64_t>> near_homes(static_cast<std::size_t>(threads));
    if (max_radius > 0) {
        const CubeIndex hindex(homes, 2 * max_radius, used, 1);
        const auto home_of = hindex.original_indices();
#pragma omp parallel num_threads(threads)
        {
            std::vector<std::uint64_t>& out =
                near_homes[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 256)
            for (std::size_t s = 0; s < surfaces.size(); ++s) {
                if (!used[s]) continue;
                const Surface& a = surfaces[s];
                // Each pair once (t > s).
                for_each_home_near(
                    hindex, a.home, a.radius + max_radius,
                    [&](std::uint32_t j) { return home_of[j] > s; },
                    [&](std::uint32_t j) {
                        const std::uint32_t t = home_of[j];
                        if ((surfaces[t].home - a.home).norm() <= a.radius + surfaces[t].radius)
                            out.push_back(pair_key(static_cast<std::uint32_t>(s), t));
                    });
            }
        }
    }
    const std::vector<std::uint64_t> packed = merged_unique({&found, &near_homes});
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(packed.size());
    for (std::size_t k = 0; k < packed.size(); ++k)
        pairs[k] = {static_cast<std::uint32_t>(packed[k] >> 32),
                    static_cast<std::uint32_t>(packed[k] & 0xffffffffu)};
    return pairs;
}

}  // namespace surfgrow
