// Distribution summaries: known answers for mean, median, nearest-rank p95, max.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "surfgrow/eval/distribution.hpp"

namespace surfgrow::eval {
namespace {

TEST(Distribution, KnownAnswersForOneToTen) {
    std::vector<double> v = {7, 3, 10, 1, 5, 9, 2, 8, 4, 6};
    const Distribution d = summarize(v);
    EXPECT_EQ(d.count, 10u);
    EXPECT_DOUBLE_EQ(d.mean, 5.5);
    EXPECT_DOUBLE_EQ(d.median, 5.5);  // mean of the two middle values
    EXPECT_DOUBLE_EQ(d.p95, 10.0);    // ceil(9.5) = 10th smallest
    EXPECT_DOUBLE_EQ(d.max, 10.0);
}

TEST(Distribution, OddCountAndNearestRank) {
    std::vector<double> v;
    for (int i = 100; i >= 1; --i) v.push_back(i);
    v.push_back(1000);  // 101 values
    const Distribution d = summarize(v);
    EXPECT_DOUBLE_EQ(d.median, 51.0);
    EXPECT_DOUBLE_EQ(d.p95, 96.0);  // ceil(0.95 * 101) = 96th smallest
    EXPECT_DOUBLE_EQ(d.max, 1000.0);
    std::vector<double> w = {4, 1, 3, 2};
    EXPECT_DOUBLE_EQ(quantile(w, 0.5), 2.0);
    EXPECT_DOUBLE_EQ(quantile(w, 1.0), 4.0);
}

TEST(Distribution, EmptyIsNaN) {
    std::vector<double> v;
    const Distribution d = summarize(v);
    EXPECT_EQ(d.count, 0u);
    EXPECT_TRUE(std::isnan(d.mean));
    EXPECT_TRUE(std::isnan(d.median));
    EXPECT_TRUE(std::isnan(d.p95));
    EXPECT_TRUE(std::isnan(quantile(v, 0.5)));
}

TEST(Distribution, OrderDoesNotChangeAnyBit) {
    std::vector<double> a, b;
    for (int i = 0; i < 1000; ++i) a.push_back(std::sin(i) * 1e-3 + 1.0 / (i + 1));
    b.assign(a.rbegin(), a.rend());
    const Distribution da = summarize(a), db = summarize(b);
    EXPECT_EQ(da.mean, db.mean);
    EXPECT_EQ(da.median, db.median);
    EXPECT_EQ(da.p95, db.p95);
}

}  // namespace
}  // namespace surfgrow::eval
