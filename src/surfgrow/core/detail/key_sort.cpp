#include "surfgrow/core/detail/key_sort.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cassert>

namespace surfgrow::detail {

namespace {

// Up to 4096 buckets: a thread's histogram (uint32) is 16 KB, inside L1. Typical keys (24-36 bits)
// then sort in 2-3 passes.
constexpr int kMaxDigitBits = 12;

}  // namespace

void radix_sort_pairs(BulkVector<std::uint64_t>& keys, BulkVector<std::uint32_t>& values,
                      int key_bits, int threads) {
    assert(keys.size() == values.size());
    const std::size_t n = keys.size();
    if (n < 2 || key_bits <= 0) return;
    const int passes = (key_bits + kMaxDigitBits - 1) / kMaxDigitBits;
    const int digit_bits = (key_bits + passes - 1) / passes;  // balanced digits
    const std::size_t buckets = std::size_t{1} << digit_bits;
    const std::uint64_t mask = buckets - 1;

    // Small inputs are not worth a thread team.
    const int team = n < (1u << 16) ? 1 : std::max(1, threads);
    BulkVector<std::uint64_t> key_tmp(n);
    BulkVector<std::uint32_t> val_tmp(n);
    std::vector<std::uint32_t> hist(static_cast<std::size_t>(team) * buckets);

    for (int pass = 0; pass < passes; ++pass) {
        const int shift = pass * digit_bits;
        std::fill(hist.begin(), hist.end(), 0u);
        bool skip = false;  // every key has the same digit: nothing moves
#pragma omp parallel num_threads(team)
        {
            const auto t = static_cast<std::size_t>(omp_get_thread_num());
            const auto nt = static_cast<std::size_t>(omp_get_num_threads());
            const std::size_t begin = n * t / nt, end = n * (t + 1) / nt;
            std::uint32_t* h = &hist[t * buckets];
            for (std::size_t i = begin; i < end; ++i) ++h[(keys[i] >> shift) & mask];
#pragma omp barrier
#pragma omp single
            {
                // Exclusive prefix over (bucket, thread): thread t's slice of bucket b follows
                // threads < t, which keeps the sort stable.
                std::uint32_t sum = 0;
                for (std::size_t b = 0; b < buckets; ++b) {
                    std::uint32_t bucket_total = 0;
                    for (std::size_t u = 0; u < nt; ++u) {
                        const std::uint32_t c = hist[u * buckets + b];
                        hist[u * buckets + b] = sum;
                        sum += c;
                        bucket_total += c;
                    }
                    if (bucket_total == n) skip = true;
                }
            }
            if (!skip) {
                for (std::size_t i = begin; i < end; ++i) {
                    const std::uint32_t pos = h[(keys[i] >> shift) & mask]++;
                    key_tmp[pos] = keys[i];
                    val_tmp[pos] = values[i];
                }
            }
        }
        if (!skip) {
            keys.swap(key_tmp);
            values.swap(val_tmp);
        }
    }
}

}  // namespace surfgrow::detail
