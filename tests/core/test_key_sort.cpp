#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "surfgrow/core/detail/key_sort.hpp"

namespace surfgrow::detail {
namespace {

struct Case {
    std::size_t n;
    int bits;
    int threads;
};

class KeySortTest : public ::testing::TestWithParam<Case> {};

TEST_P(KeySortTest, MatchesStableSort) {
    const auto [n, bits, threads] = GetParam();
    std::mt19937_64 rng(n * 31 + static_cast<unsigned>(bits));
    const std::uint64_t mask = bits == 64 ? ~0ull : ((1ull << bits) - 1);
    BulkVector<std::uint64_t> keys(n);
    // Few distinct keys in half the cases, so stability is exercised.
    for (auto& k : keys) k = (rng() & mask) % (n % 2 ? mask : 97);
    BulkVector<std::uint32_t> values(n);
    std::iota(values.begin(), values.end(), 0u);

    std::vector<std::pair<std::uint64_t, std::uint32_t>> expected(n);
    for (std::size_t i = 0; i < n; ++i) expected[i] = {keys[i], values[i]};
    std::stable_sort(expected.begin(), expected.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });

    radix_sort_pairs(keys, values, bits, threads);
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(keys[i], expected[i].first) << "at " << i;
        ASSERT_EQ(values[i], expected[i].second) << "at " << i;
    }
}

INSTANTIATE_TEST_SUITE_P(Sizes, KeySortTest,
                         ::testing::Values(Case{0, 10, 1}, Case{1, 10, 2}, Case{1000, 7, 1},
                                           Case{1001, 33, 2}, Case{70000, 22, 1},
                                           Case{70001, 22, 2}, Case{200000, 45, 3},
                                           Case{200001, 63, 2}));

}  // namespace
}  // namespace surfgrow::detail
