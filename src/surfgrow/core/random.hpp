// A small, fully specified random generator: the same numbers on every platform and library.
#pragma once

#include <cstdint>
#include <span>
#include <utility>

namespace surfgrow {

/// SplitMix64 (Steele, Lea, Flood 2014). std::shuffle and the std distributions are not
/// specified bit for bit, so results would differ between standard libraries; this is.
class SplitMix64 {
  public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform integer in [0, bound) by Lemire's multiply-shift (bias below 2^-32 for bound <
    /// 2^32).
    std::uint32_t below(std::uint32_t bound) {
        return static_cast<std::uint32_t>(((next() >> 32) * std::uint64_t{bound}) >> 32);
    }
    /// Uniform double in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  private:
    std::uint64_t state_;
};

/// Mixes a seed with a stream number (a block id, a scan id) into an independent seed.
[[nodiscard]] inline std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
    SplitMix64 g(seed ^ (stream * 0xD1B54A32D192ED03ull));
    g.next();
    return g.next();
}

/// Fisher-Yates shuffle driven by SplitMix64.
template <class T>
void shuffle(std::span<T> items, SplitMix64& rng) {
    for (std::size_t i = items.size(); i > 1; --i) {
        const std::size_t j = rng.below(static_cast<std::uint32_t>(i));
        std::swap(items[i - 1], items[j]);
    }
}

}  // namespace surfgrow
