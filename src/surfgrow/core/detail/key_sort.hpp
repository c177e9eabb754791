// Stable radix sort of (key, value) pairs: the O(N) heart of the cube index.
#pragma once

#include <cstdint>
#include "surfgrow/core/detail/bulk_allocator.hpp"

namespace surfgrow::detail {

/// Sorts `keys` ascending by their low `key_bits` bits, carrying `values` along, in
/// ceil(key_bits / 11) counting passes. Stable, so the result is the same for any `threads`
/// (the work is split into contiguous chunks, one per thread, with per-chunk histograms).
/// Bits above `key_bits` must be zero. `keys.size()` must equal `values.size()`.
void radix_sort_pairs(BulkVector<std::uint64_t>& keys, BulkVector<std::uint32_t>& values,
                      int key_bits, int threads);

}  // namespace surfgrow::detail
