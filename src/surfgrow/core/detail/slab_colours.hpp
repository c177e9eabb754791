// Slabs of one colour in parallel (internal, for the grower's own sources, which build with
// OpenMP): growing and strips run the even slabs at once and then the odd ones.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/grow_context.hpp"

namespace surfgrow::detail {

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

}  // namespace surfgrow::detail
