// Eq. (1) on hand-made readings: trimming, missing and out-of-range readings, bad parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/scanner/range_filter.hpp"

namespace {

using surfgrow::Error;
using surfgrow::ErrorCode;
using surfgrow::scanner::RangeFilter;

double run(const RangeFilter& f, std::vector<std::uint16_t> r) {
    return f(r);
}

TEST(RangeFilter, TrimsQFromEachEndAndAveragesTheRest) {
    const RangeFilter f(5, 1, 20, 4000);
    // Sorted: 1000 1002 1004 1006 3000 -> mean of 1002 1004 1006.
    EXPECT_DOUBLE_EQ(run(f, {1006, 3000, 1000, 1004, 1002}), 1004.0);
    // An outlier on each side is removed.
    EXPECT_DOUBLE_EQ(run(f, {25, 1001, 1002, 1003, 3999}), 1002.0);
}

TEST(RangeFilter, QZeroIsThePlainMean) {
    const RangeFilter f(4, 0, 20, 4000);
    EXPECT_DOUBLE_EQ(run(f, {1000, 1001, 1002, 1003}), 1001.5);
}

TEST(RangeFilter, LargerQKeepsTheMiddle) {
    const RangeFilter f(7, 2, 20, 4000);
    // Sorted: 500 900 1000 1010 1020 1100 4000 -> mean of 1000 1010 1020.
    EXPECT_DOUBLE_EQ(run(f, {1100, 500, 1010, 4000, 1000, 900, 1020}), 1010.0);
    const RangeFilter median(3, 1, 20, 4000);
    EXPECT_DOUBLE_EQ(run(median, {1500, 1000, 2000}), 1500.0);
}

TEST(RangeFilter, MissingReadingsAreNotAveragedAndQIsStillTrimmed) {
    const RangeFilter f(5, 1, 20, 4000);
    // Four valid: trim one each side -> mean of the middle two.
    EXPECT_DOUBLE_EQ(run(f, {1000, 0, 1010, 1002, 1004}), 1003.0);
    // Three valid: their median.
    EXPECT_DOUBLE_EQ(run(f, {0, 1000, 1003, 1009, 0}), 1003.0);
    // Two valid (<= 2q): no range.
    EXPECT_TRUE(std::isnan(run(f, {0, 0, 0, 1000, 1001})));
    EXPECT_TRUE(std::isnan(run(f, {0, 0, 0, 0, 0})));
}

TEST(RangeFilter, OutOfRangeReadingsAreNotAveraged) {
    const RangeFilter f(5, 1, 20, 4000);
    // 15 is a URG error code (< 20 mm), 4500 is beyond the 4000 mm limit: three valid remain.
    EXPECT_DOUBLE_EQ(run(f, {15, 4500, 1000, 1001, 1002}), 1001.0);
    // Limits are inclusive.
    EXPECT_DOUBLE_EQ(run(f, {20, 20, 20, 4000, 4000}), 20.0 + (4000 - 20) / 3.0);
    // Narrower limits exclude more.
    const RangeFilter narrow(5, 1, 500, 1500);
    EXPECT_DOUBLE_EQ(run(narrow, {400, 1000, 1001, 1002, 1600}), 1001.0);
}

TEST(RangeFilter, RejectsNNotAboveTwoQ) {
    for (const auto& [n, q] : std::vector<std::pair<int, int>>{{2, 1}, {4, 2}, {1, 1}, {0, 0}}) {
        try {
            RangeFilter f(n, q, 20, 4000);
            FAIL() << "n = " << n << ", q = " << q << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
            EXPECT_NE(std::string(e.what()).find("n > 2q"), std::string::npos) << e.what();
        }
    }
}

TEST(RangeFilter, RejectsNegativeQAndBadLimits) {
    EXPECT_THROW(RangeFilter(5, -1, 20, 4000), Error);
    EXPECT_THROW(RangeFilter(5, 1, 0, 4000), Error);
    EXPECT_THROW(RangeFilter(5, 1, 4000, 4000), Error);
    EXPECT_THROW(RangeFilter(5, 1, 4000, 20), Error);
}

}  // namespace
