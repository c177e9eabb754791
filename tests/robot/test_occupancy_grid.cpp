// The occupancy grid against brute force: the set of cubes of registered points, and occupied().
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "support/test_support.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"
#include "surfgrow/robot/sensor_origins.hpp"

namespace surfgrow {
namespace {

using Key = std::tuple<int, int, int>;

// The cube of a point by the grid's own definition, written out: float local coordinates
// relative to the origin, floor of local / side.
Key cube_of(const Vec3d& p, const Vec3d& origin, double side) {
    const Vec3f local = (p - origin).cast<float>();
    return {static_cast<int>(std::floor(double(local.x()) / side)),
            static_cast<int>(std::floor(double(local.y()) / side)),
            static_cast<int>(std::floor(double(local.z()) / side))};
}

PointCloud box_cloud() {
    PointCloud cloud;
    std::mt19937_64 rng(5);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    std::uniform_real_distribution<float> u(-0.5f, 1.0f);
    for (int i = 0; i < 300; ++i) cloud.points.push_back({u(rng), u(rng), u(rng)});  // noise
    for (std::size_t i = 7; i < cloud.size(); i += 501)
        cloud.points[i] = Vec3f::Constant(std::nanf(""));
    return cloud;
}

// The grid of a grow result equals the brute-force set of cubes of registered points, on the
// grower's alignment (origin = lowest grown point less 1.5 cubes, side = mu (1 + 2^-20)).
void check_against_brute_force(const PointCloud& cloud, const GrowerConfig& config) {
    const GrowResult result = grow_surfaces(cloud, config);
    const OccupancyGrid grid = occupancy_grid(cloud, result, config);

    const std::vector<std::uint8_t> mask = grown_point_mask(cloud, config);
    Aabb grown;
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (mask[i]) grown.add(cloud.points[i].cast<double>());
    const double side = config.mu * (1.0 + 1.0 / (1 << 20));
    EXPECT_DOUBLE_EQ(grid.mu(), config.mu);
    EXPECT_DOUBLE_EQ(grid.cube_size(), side);
    if (!grown.empty()) {
        EXPECT_TRUE(grid.origin().isApprox(grown.min - Vec3d::Constant(1.5 * side), 1e-12));
    }

    std::set<Key> expected;
    std::map<Key, std::uint32_t> count;
    std::uint64_t registered = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (result.labels[i] < 0) continue;
        const Key k = cube_of(cloud.points[i].cast<double>(), grid.origin(), grid.cube_size());
        expected.insert(k);
        ++count[k];
        ++registered;
    }
    std::set<Key> got;
    Key previous{-1, -1, -1};
    for (std::size_t c = 0; c < grid.size(); ++c) {
        const CellCoords& cell = grid.cells()[c];
        const Key k{cell.x(), cell.y(), cell.z()};
        EXPECT_LT(previous, k) << "cells must be sorted and unique";
        previous = k;
        got.insert(k);
        EXPECT_EQ(grid.point_counts()[c], count[k]);
    }
    EXPECT_EQ(got, expected);
    EXPECT_EQ(grid.registered_points(), registered);
    EXPECT_EQ(registered, result.stats.registered);

    // Every registered point is in an occupied cube; random positions agree with the set.
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (result.labels[i] >= 0) {
            ASSERT_TRUE(grid.occupied(Vec3d(cloud.points[i].cast<double>())));
        }
    std::mt19937_64 rng(11);
    const Aabb box = grid.bounds();
    std::uniform_real_distribution<double> ux(box.min.x() - 0.05, box.max.x() + 0.05);
    std::uniform_real_distribution<double> uy(box.min.y() - 0.05, box.max.y() + 0.05);
    std::uniform_real_distribution<double> uz(box.min.z() - 0.05, box.max.z() + 0.05);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        // Half near registered points (hits likely), half anywhere in the box.
        Vec3d p(ux(rng), uy(rng), uz(rng));
        if (i % 2 == 0) {
            const Vec3f& q = cloud.points[rng() % cloud.size()];
            if (is_finite(q)) p = q.cast<double>() + 0.5 * config.mu * Vec3d::Random();
        }
        const bool want = expected.count(cube_of(p, grid.origin(), grid.cube_size())) > 0;
        ASSERT_EQ(grid.occupied(p), want) << p.transpose();
        hits += want ? 1 : 0;
    }
    EXPECT_GT(hits, 1000);  // the test exercises both answers
    EXPECT_FALSE(grid.occupied(Vec3d(Vec3d::Constant(std::nan("")))));
    // Bounds: the union of the occupied cubes.
    for (const CellCoords& c : grid.cells()) EXPECT_TRUE(box.contains(grid.centre(c)));
}

TEST(OccupancyGrid, EqualsTheCubesOfRegisteredPoints) {
    GrowerConfig config;
    config.threads = 2;
    check_against_brute_force(box_cloud(), config);
}

TEST(OccupancyGrid, LargerMuAndNoLeftoverPass) {
    GrowerConfig config;
    config.mu = 0.03;
    config.attach_leftovers = false;
    check_against_brute_force(box_cloud(), config);
}

TEST(OccupancyGrid, FollowsTheCropLikeTheGrower) {
    GrowerConfig config;
    config.crop.radius = 0.3;
    config.crop.center = Vec3d(0.1, 0, 0.55);
    const PointCloud cloud = box_cloud();
    check_against_brute_force(cloud, config);
    // Cropped points are never occupied, even where they are dense.
    const GrowResult r = grow_surfaces(cloud, config);
    const OccupancyGrid grid = occupancy_grid(cloud, r, config);
    EXPECT_GT(r.stats.cropped_points, 0u);
    for (const CellCoords& c : grid.cells())
        EXPECT_LE((grid.centre(c) - *config.crop.center).norm(), 0.3 + grid.cube_size());
}

TEST(OccupancyGrid, CloudWithAnOffsetUsesItsLocalFrame) {
    PointCloud cloud = box_cloud();
    cloud.offset = Vec3d(500000, 6000000, 30);
    GrowerConfig config;
    check_against_brute_force(cloud, config);
}

TEST(OccupancyGrid, ClustersAMillionMetresApartOnTheGridNotTheRanks) {
    // Too wide for packed grid keys: the grower's index ranks its cubes, the grid stays a grid.
    PointCloud cloud;
    test::lattice_patches(1.0 / 16, Vec3d::Zero(), 1, cloud.points);
    test::lattice_patches(1.0 / 16, Vec3d::Constant(1e6), 2, cloud.points);
    GrowerConfig config;
    config.mu = 0.25;
    ASSERT_TRUE(CubeIndex(cloud.points, config.mu).ranked());
    check_against_brute_force(cloud, config);
    // A far outlier puts the grid's origin 1e30 m from the registered cubes along x (where floats
    // flatten the clusters, which still grow along y and z): refused, not wrapped.
    cloud.points.emplace_back(-1e30f, 0.f, 0.f);
    const GrowResult r = grow_surfaces(cloud, config);
    ASSERT_GT(r.stats.registered, 0u);
    try {
        (void)occupancy_grid(cloud, r, config);
        ADD_FAILURE() << "a grid of 4e30 cubes";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
        EXPECT_NE(std::string(e.what()).find("2^31 cubes"), std::string::npos) << e.what();
    }
}

TEST(OccupancyGrid, EmptyCloudsAndCloudsWithoutRegisteredPoints) {
    GrowerConfig config;
    for (const std::size_t n : {std::size_t{0}, std::size_t{5}}) {
        PointCloud cloud;
        cloud.points.assign(n, Vec3f::Constant(std::nanf("")));
        const GrowResult r = grow_surfaces(cloud, config);
        const OccupancyGrid grid = occupancy_grid(cloud, r, config);
        EXPECT_TRUE(grid.empty());
        EXPECT_EQ(grid.size(), 0u);
        EXPECT_TRUE(grid.bounds().empty());
        EXPECT_FALSE(grid.occupied(Vec3d(0, 0, 0)));
        EXPECT_DOUBLE_EQ(grid.mu(), config.mu);
    }
    // Isolated points: grown (indexed) but never registered.
    PointCloud sparse;
    sparse.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const GrowResult r = grow_surfaces(sparse, config);
    const OccupancyGrid grid = occupancy_grid(sparse, r, config);
    EXPECT_TRUE(grid.empty());
    EXPECT_FALSE(grid.occupied(Vec3d(0, 0, 0)));
    const OccupancyGrid none;
    EXPECT_TRUE(none.empty());
}

TEST(OccupancyGrid, RejectsLabelsThatAreNotThoseOfTheCloud) {
    const PointCloud cloud = box_cloud();
    GrowerConfig config;
    const GrowResult r = grow_surfaces(cloud, config);
    std::vector<std::int32_t> labels = r.labels;
    labels.pop_back();
    try {
        (void)occupancy_grid(cloud, labels, config);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
    }
    labels = r.labels;
    labels[7] = 0;  // a NaN point, labelled
    try {
        (void)occupancy_grid(cloud, labels, config);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
        EXPECT_NE(std::string(e.what()).find("point 7"), std::string::npos) << e.what();
    }
}

TEST(SensorOrigins, ScanOriginsThenViewpointElseNone) {
    PointCloud cloud;
    cloud.points = {{0, 0, 0}, {1, 0, 0}};
    GrowerConfig config;
    EXPECT_FALSE(sensor_origins(cloud, config).known());
    cloud.viewpoint = Vec3d(0, 0, 1);
    SensorOrigins s = sensor_origins(cloud, config);
    ASSERT_EQ(s.source, SensorOrigins::Source::kViewpoint);
    EXPECT_EQ(*s.origin_of(cloud, 1), Vec3d(0, 0, 1));
    config.viewpoint = Vec3d(0, 0, 2);  // the given one wins over the file's
    EXPECT_EQ(*sensor_origins(cloud, config).origin_of(cloud, 0), Vec3d(0, 0, 2));
    cloud.scan_index = {0, 1};
    cloud.scan_origins = {Vec3d(1, 1, 1)};
    s = sensor_origins(cloud, config);
    ASSERT_EQ(s.source, SensorOrigins::Source::kScanOrigins);
    EXPECT_EQ(*s.origin_of(cloud, 0), Vec3d(1, 1, 1));
    EXPECT_EQ(s.origin_of(cloud, 1), nullptr);  // scan 1 has no origin: no ray
}

}  // namespace
}  // namespace surfgrow
