// A map's occupancy grid extended by its new points (OccupancyMemo) against the grid of the whole
// cloud built anew: the same cells, counts and origin; set aside wherever that could differ.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/test_support.hpp"
#include "surfgrow/core/grown_points.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/robot/occupancy_memo.hpp"

namespace surfgrow {
namespace {

// A box's faces, noise points and NaNs, with the grown points' lowest x, y and z first: every
// prefix of it keeps the low corner, so extending a prefix's grid never moves the origin.
PointCloud corner_first_cloud(const GrowerConfig& config) {
    PointCloud cloud;
    cloud.viewpoint = Vec3d(0.05, -0.4, 0.5);  // the radius crop's centre
    std::mt19937_64 rng(5);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    std::shuffle(cloud.points.begin(), cloud.points.end(), rng);
    std::uniform_real_distribution<float> u(-0.3f, 0.3f);
    for (int i = 0; i < 300; ++i) cloud.points.push_back({u(rng), u(rng), 0.55f + u(rng)});
    for (std::size_t i = 7; i < cloud.size(); i += 501)
        cloud.points[i] = Vec3f::Constant(std::nanf(""));
    const std::vector<std::uint8_t> grown = grown_point_mask(cloud, config);
    for (int a = 0; a < 3; ++a) {
        std::size_t low = 0;
        while (!grown[low]) ++low;
        for (std::size_t i = low; i < cloud.size(); ++i)
            if (grown[i] && cloud.points[i][a] < cloud.points[low][a]) low = i;
        std::swap(cloud.points[static_cast<std::size_t>(a) + 10], cloud.points[low]);
    }
    return cloud;
}

Aabb grown_box(const CloudView& cloud, const GrowerConfig& config) {
    const std::vector<std::uint8_t> grown = grown_point_mask(cloud, config);
    Aabb box;
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (grown[i]) box.add(cloud.points[i].cast<double>());
    return box;
}

CloudView first(const PointCloud& cloud, std::size_t n) {
    CloudView v(std::span(cloud.points).first(n));
    v.viewpoint = cloud.viewpoint;
    return v;
}

void expect_same_grid(const OccupancyGrid& got, const OccupancyGrid& want) {
    EXPECT_EQ(got.origin(), want.origin());
    EXPECT_EQ(got.cube_size(), want.cube_size());
    EXPECT_EQ(got.registered_points(), want.registered_points());
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t c = 0; c < got.size(); ++c) {
        ASSERT_EQ(got.cells()[c], want.cells()[c]) << c;
        ASSERT_EQ(got.point_counts()[c], want.point_counts()[c]) << c;
    }
}

// The grid of the cloud's first n points built anew, and a memo of it.
OccupancyMemo memo_of(const PointCloud& cloud, std::span<const std::int32_t> labels, std::size_t n,
                      const GrowerConfig& config) {
    OccupancyMemo memo;
    const CloudView view = first(cloud, n);
    remember_occupancy(memo, view, labels.first(n), grown_box(view, config),
                       occupancy_grid(view, labels.first(n), config), config);
    return memo;
}

void check_extensions(const GrowerConfig& config) {
    const PointCloud cloud = corner_first_cloud(config);
    const std::vector<std::int32_t> labels = grow_surfaces(cloud, config).labels;
    const std::size_t n = cloud.size();
    OccupancyMemo memo = memo_of(cloud, labels, n / 5, config);
    for (const std::size_t upto : {n / 5 + 1, n / 2, n - 1, n}) {
        SCOPED_TRACE(upto);
        const CloudView view = first(cloud, upto);
        const std::span<const std::int32_t> some = std::span(labels).first(upto);
        const std::optional<OccupancyGrid> got = extend_occupancy(memo, view, some, config);
        ASSERT_TRUE(got.has_value());
        expect_same_grid(*got, occupancy_grid(view, some, config));
        EXPECT_EQ(memo.points, upto);
    }
    EXPECT_GT(memo.grid->size(), 100u);
}

TEST(OccupancyMemo, ExtendedGridIsTheGridOfTheWholeCloud) {
    GrowerConfig config;
    check_extensions(config);
}

TEST(OccupancyMemo, ExtendedGridFollowsTheCropLikeTheGrower) {
    GrowerConfig config;
    config.crop.radius = 0.3;  // about the cloud's viewpoint
    check_extensions(config);
    config.crop.radius.reset();
    config.crop.box = Aabb{Vec3d(-0.15, -1, 0.35), Vec3d(0.15, 1, 0.8)};
    check_extensions(config);
}

TEST(OccupancyMemo, SetAsideWhereTheGridCouldDiffer) {
    const GrowerConfig config;
    PointCloud cloud = corner_first_cloud(config);
    std::vector<std::int32_t> labels = grow_surfaces(cloud, config).labels;
    const std::size_t half = cloud.size() / 2, n = cloud.size();
    const auto refused = [&](OccupancyMemo memo, const CloudView& view,
                             std::span<const std::int32_t> l, const GrowerConfig& c) {
        const std::size_t before = memo.points;
        const bool none = !extend_occupancy(memo, view, l, c).has_value();
        return none && memo.points == before;  // and the memo left as it was
    };
    const OccupancyMemo memo = memo_of(cloud, labels, half, config);
    ASSERT_FALSE(refused(memo, cloud, labels, config));

    EXPECT_TRUE(refused(OccupancyMemo{}, cloud, labels, config));  // an empty memo
    EXPECT_TRUE(refused(memo, first(cloud, half - 1), std::span(labels).first(half - 1), config));
    GrowerConfig other = config;
    other.mu *= 2;
    EXPECT_TRUE(refused(memo, cloud, labels, other));
    other = config;
    other.crop.radius = 10.0;
    EXPECT_TRUE(refused(memo, cloud, labels, other));
    // A new point below the low corner moves the origin.
    PointCloud lower = cloud;
    lower.points[n - 3].z() = -1.0f;
    EXPECT_TRUE(refused(memo, lower, labels, config));
    // A covered point moved, or relabelled: not the cloud the memo saw.
    PointCloud moved = cloud;
    moved.points[half - 1].x() += 0.001f;
    EXPECT_TRUE(refused(memo, moved, labels, config));
    std::vector<std::int32_t> relabelled = labels;
    for (std::size_t i = 0; i < half; ++i)
        if (relabelled[i] >= 0) {
            relabelled[i] = -1;
            break;
        }
    EXPECT_TRUE(refused(memo, cloud, relabelled, config));
    // A registered new point the grower could not have grown (NaN).
    PointCloud nan = cloud;
    std::size_t k = half;
    while (labels[k] < 0) ++k;
    nan.points[k] = Vec3f::Constant(std::nanf(""));
    EXPECT_TRUE(refused(memo, nan, labels, config));
}

TEST(OccupancyGrid, AddRegisteredMergesCountsInOrder) {
    OccupancyGrid grid(0.01);
    grid.add_registered({{1, 2, 3}, {0, 5, 5}, {1, 2, 3}});
    grid.add_registered({{1, 2, 2}, {1, 2, 3}, {2, 0, 0}});
    ASSERT_EQ(grid.size(), 4u);
    EXPECT_EQ(grid.cells()[0], CellCoords(0, 5, 5));
    EXPECT_EQ(grid.cells()[1], CellCoords(1, 2, 2));
    EXPECT_EQ(grid.cells()[2], CellCoords(1, 2, 3));
    EXPECT_EQ(grid.cells()[3], CellCoords(2, 0, 0));
    EXPECT_EQ(grid.point_counts()[2], 3u);
    EXPECT_EQ(grid.registered_points(), 6u);
    grid.add_registered({});
    EXPECT_EQ(grid.registered_points(), 6u);
}

}  // namespace
}  // namespace surfgrow
