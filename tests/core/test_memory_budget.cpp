// The memory budget: the machine's memory, or SURFGROW_MEMORY_LIMIT; over it, a clear error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/memory_budget.hpp"
#include "surfgrow/core/surface_grower.hpp"

namespace surfgrow {
namespace {

// Sets SURFGROW_MEMORY_LIMIT for one scope.
class Limit {
  public:
    explicit Limit(const char* value) { ::setenv("SURFGROW_MEMORY_LIMIT", value, 1); }
    ~Limit() { ::unsetenv("SURFGROW_MEMORY_LIMIT"); }
    Limit(const Limit&) = delete;
    Limit& operator=(const Limit&) = delete;
};

TEST(MemoryBudget, IsTheMachinesMemoryUnlessTheVariableSaysLess) {
    ::unsetenv("SURFGROW_MEMORY_LIMIT");
    EXPECT_GT(memory_budget(), 64ull << 20);  // any machine that builds surfgrow
    {
        const Limit l("1234");
        EXPECT_EQ(memory_budget(), 1234u);
    }
    {
        const Limit l("3k");
        EXPECT_EQ(memory_budget(), 3u * 1024);
    }
    {
        const Limit l("2G");
        EXPECT_EQ(memory_budget(), 2ull << 30);
    }
    for (const char* bad : {"abc", "12X", "-5", "1.5G", "G", "99999999999999999999"}) {
        const Limit l(bad);
        try {
            (void)memory_budget();
            ADD_FAILURE() << bad << " was taken";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kUsage) << bad;
            EXPECT_NE(std::string(e.what()).find("SURFGROW_MEMORY_LIMIT"), std::string::npos);
        }
    }
}

TEST(MemoryBudget, MoreThanTheBudgetIsCloudTooLargeNamingTheWork) {
    const Limit l("1M");
    check_memory(1024.0 * 1024, "just enough");  // no error at the budget itself
    try {
        check_memory(5e6, "x.json: parsing its 1 MB of JSON");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
        const std::string m = e.what();
        EXPECT_NE(m.find("x.json: parsing"), std::string::npos) << m;
        EXPECT_NE(m.find("5 MB"), std::string::npos) << m;
        EXPECT_NE(m.find("SURFGROW_MEMORY_LIMIT allows"), std::string::npos) << m;
    }
}

// Growing refuses a cloud whose index and buffers would not fit, before allocating them, and
// names what to do; a crop that leaves few points in fits.
TEST(MemoryBudget, GrowingACloudBeyondTheBudgetIsRefusedUpFront) {
    PointCloud cloud;  // 200 000 points on a 4 m x 5 m floor: 1.6 MB of positions
    for (int i = 0; i < 400; ++i)
        for (int j = 0; j < 500; ++j)
            cloud.points.emplace_back(0.01f * float(i), 0.01f * float(j), 0.0f);
    GrowerConfig config;
    config.mu = 0.03;
    {
        const Limit l("4M");  // the growing needs about 200000 * 72 B = 14 MB
        try {
            (void)grow_surfaces(cloud, config);
            FAIL() << "no error";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
            const std::string m = e.what();
            EXPECT_NE(m.find("growing 200000 points needs about 14 MB"), std::string::npos) << m;
            EXPECT_NE(m.find("crop the workspace"), std::string::npos) << m;
        }
        // A crop to 0.5 m around a corner indexes 2 000 points: that fits.
        config.crop.radius = 0.5;
        config.crop.center = Vec3d(0, 0, 0);
        const GrowResult r = grow_surfaces(cloud, config);
        EXPECT_GT(r.stats.registered, 1500u);
    }
    config.crop = {};
    EXPECT_GT(grow_surfaces(cloud, config).stats.registered, 190000u);  // no limit: it grows
}

}  // namespace
}  // namespace surfgrow
