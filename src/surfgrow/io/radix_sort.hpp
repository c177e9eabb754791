// LSD radix sort of 64-bit keys (internal to io): linear in millions of leaf keys and rays.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace surfgrow::io {

/// Sorts `v` ascending on the low `bits` bits of each key (the bits above must be zero), 16 bits
/// a pass.
inline void radix_sort(std::vector<std::uint64_t>& v, int bits) {
    std::vector<std::uint64_t> tmp(v.size());
    std::vector<std::size_t> count(std::size_t{1} << 16);
    for (int shift = 0; shift < bits; shift += 16) {
        std::fill(count.begin(), count.end(), 0);
        for (const std::uint64_t x : v) ++count[(x >> shift) & 0xffff];
        std::size_t sum = 0;
        for (std::size_t& c : count) sum += std::exchange(c, sum);
        for (const std::uint64_t x : v) tmp[count[(x >> shift) & 0xffff]++] = x;
        v.swap(tmp);
    }
}

}  // namespace surfgrow::io
