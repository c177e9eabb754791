#include "surfgrow/core/detail/cube_surfaces.hpp"

#include <omp.h>

#include <cstddef>

#include "surfgrow/core/detail/parallel_errors.hpp"

namespace surfgrow::detail {

CubeSurfaces cube_surfaces(const CubeIndex& index, std::span<const std::int32_t> labels,
                           std::int32_t first_surface, int threads) {
    const std::size_t cubes = index.cube_count();
    CubeSurfaces cs;
    cs.start.assign(cubes + 1, 0);
    // Chunks of cubes, each listing its own; concatenated in cube order afterwards.
    const std::size_t chunks = std::min<std::size_t>(cubes, 64 * static_cast<std::size_t>(threads));
    std::vector<std::vector<std::int32_t>> part(chunks);
    ParallelErrors errors;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::size_t k = 0; k < chunks; ++k) {
        errors.run(k, [&] {
            // Locals, not the captures: the compiler reloads what a push_back might alias.
            const std::int32_t* const lab = labels.data();
            const std::int32_t lowest = first_surface;
            // Filled here and moved: neighbouring chunks' vectors share a cache line (written in
            // place, two threads were no faster than one).
            std::vector<std::int32_t> out;
            for (std::size_t c = k * cubes / chunks; c < (k + 1) * cubes / chunks; ++c) {
                // A cube holds a few surfaces: each new one is inserted in order in place (no
                // sort call per cube, which cost more than the scan); past kSorted, sorted after.
                constexpr std::size_t kSorted = 16;
                const std::size_t first = out.size();
                std::int32_t last = -1;
                const std::uint32_t end = index.cube_end(c);
                for (std::uint32_t i = index.cube_begin(c); i < end; ++i) {
                    const std::int32_t l = lab[i];
                    if (l < lowest || l == last) continue;
                    last = l;
                    std::size_t at = out.size();
                    if (at - first < kSorted) {
                        while (at > first && out[at - 1] > l) --at;
                        if (at > first && out[at - 1] == l) continue;
                    }
                    out.insert(out.begin() + static_cast<std::ptrdiff_t>(at), l);
                }
                if (out.size() - first > kSorted) {
                    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
                    out.erase(
                        std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end()),
                        out.end());
                }
                cs.start[c + 1] = static_cast<std::uint32_t>(out.size() - first);
            }
            part[k] = std::move(out);
        });
    }
    errors.rethrow();
    for (std::size_t c = 0; c < cubes; ++c) cs.start[c + 1] += cs.start[c];
    cs.ids.reserve(cs.start[cubes]);
    for (const auto& p : part) cs.ids.insert(cs.ids.end(), p.begin(), p.end());
    return cs;
}

}  // namespace surfgrow::detail
