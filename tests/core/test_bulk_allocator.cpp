#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "surfgrow/core/detail/bulk_allocator.hpp"

namespace surfgrow::detail {
namespace {

TEST(BulkAllocator, BigBlocksAreHugePageAlignedAndHoldTheirData) {
    for (const std::size_t n : {std::size_t{1} << 19, (std::size_t{5} << 20) / 4 + 3}) {
        BulkVector<std::uint32_t> v(n);
        ASSERT_GE(n * sizeof(std::uint32_t), kHugePage);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHugePage, 0u) << n;
        std::iota(v.begin(), v.end(), 7u);
        v.push_back(1);  // grows: a new mapping, the old one copied and unmapped
        EXPECT_EQ(v[0], 7u);
        EXPECT_EQ(v[n - 1], static_cast<std::uint32_t>(n - 1 + 7));
        EXPECT_EQ(v.back(), 1u);
    }
}

TEST(BulkAllocator, SmallBlocksComeFromTheHeap) {
    BulkVector<double> v(100, 2.5);
    EXPECT_EQ(v.size(), 100u);
    EXPECT_EQ(v[99], 2.5);
}

// A type aligned to a cache line is, small or big (malloc alone gives 16 bytes).
TEST(BulkAllocator, OverAlignedTypesAreAligned) {
    struct alignas(64) Line {
        double x[3];
    };
    for (const std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{1000},
                                (std::size_t{2} << 20) / sizeof(Line) + 5}) {
        for (int k = 0; k < 4; ++k) {  // several blocks, so one cannot be aligned by chance
            BulkVector<Line> v(n);
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % alignof(Line), 0u) << n;
            v[n - 1].x[2] = 1.5;
            EXPECT_EQ(v[n - 1].x[2], 1.5);
        }
    }
}

TEST(BulkAllocator, ReleaseFreesTheStorageWhereAssigningEmptyDoesNot) {
    std::vector<int> a(1000, 1);
    a = {};
    EXPECT_GE(a.capacity(), 1000u);  // why release() exists
    release(a);
    EXPECT_EQ(a.capacity(), 0u);
    BulkVector<float> b(std::size_t{1} << 20);
    release(b);
    EXPECT_EQ(b.capacity(), 0u);
}

TEST(BulkAllocator, ReserveBulkReservesAndKeepsContents) {
    std::vector<std::uint64_t> v{1, 2, 3};
    reserve_bulk(v, std::size_t{1} << 20);
    EXPECT_GE(v.capacity(), std::size_t{1} << 20);
    EXPECT_EQ(v, (std::vector<std::uint64_t>{1, 2, 3}));
}

}  // namespace
}  // namespace surfgrow::detail
