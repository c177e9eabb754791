// The pipeline: the same results as its stages called one by one (the occupancy grid on the
// grower's own index equals one rebuilt from the labels), for any thread count, with and without
// a workspace crop; its configuration checked up front; its progress in order.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/pipeline/pipeline.hpp"

namespace surfgrow {
namespace {

// A closed box and a far plate: planes, coverage, occupancy and collision all have work, and a
// radius crop around the box leaves the plate out.
PointCloud scene_cloud() {
    PointCloud cloud;
    std::mt19937_64 rng(11);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    const test::Rect plate{{0, 0, 2.0}, {1, 0, 0}, {0, 1, 0}, 0.2, 0.2};
    test::sample_rect(plate, 0.006, 0.3, 0.001, rng, cloud.points);
    cloud.points.push_back(Vec3f(std::nanf(""), 0, 0));  // an invalid point
    cloud.viewpoint = Vec3d(0, 0, 0);
    return cloud;
}

bool same_bytes(const Vec3d& a, const Vec3d& b) {
    return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

void expect_same_surfaces(const GrowResult& a, const GrowResult& b) {
    EXPECT_EQ(a.labels, b.labels);
    ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.surfaces.size(); ++i)
        differ += !same_bytes(a.surfaces[i].normal, b.surfaces[i].normal) ||
                  !same_bytes(a.surfaces[i].centroid, b.surfaces[i].centroid) ||
                  a.surfaces[i].point_count != b.surfaces[i].point_count;
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(a.stats.valid_points, b.stats.valid_points);
    EXPECT_EQ(a.stats.invalid_points, b.stats.invalid_points);
    EXPECT_EQ(a.stats.cropped_points, b.stats.cropped_points);
}

void expect_same_grid(const OccupancyGrid& a, const OccupancyGrid& b) {
    EXPECT_TRUE(same_bytes(a.origin(), b.origin()));
    EXPECT_EQ(a.cube_size(), b.cube_size());
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(std::equal(a.cells().begin(), a.cells().end(), b.cells().begin()));
    EXPECT_TRUE(
        std::equal(a.point_counts().begin(), a.point_counts().end(), b.point_counts().begin()));
    EXPECT_EQ(a.registered_points(), b.registered_points());
}

void expect_same_coverage(const CoveragePlan& a, const CoveragePlan& b) {
    ASSERT_EQ(a.goals.size(), b.goals.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.goals.size(); ++i)
        differ += !same_bytes(a.goals[i].position, b.goals[i].position) ||
                  a.goals[i].plane != b.goals[i].plane;
    EXPECT_EQ(differ, 0u);
}

class PipelineStages : public ::testing::TestWithParam<bool> {};

TEST_P(PipelineStages, EqualTheStagesCalledOneByOne) {
    const PointCloud cloud = scene_cloud();
    PipelineConfig config;
    if (GetParam()) config.grow.crop.radius = 1.0;  // around the viewpoint: the plate is out
    const PipelineResult r = run_pipeline(cloud, config);
    ASSERT_TRUE(r.planes && r.coverage && r.occupancy && r.collision);
    ASSERT_GT(r.grow.surfaces.size(), 50u);
    EXPECT_EQ(r.grow.stats.invalid_points, 1u);
    if (GetParam()) {
        EXPECT_GT(r.grow.stats.cropped_points, 1000u);  // the plate's points
    } else {
        EXPECT_EQ(r.grow.stats.cropped_points, 0u);
    }

    const GrowResult grown = grow_surfaces(cloud, config.grow);
    expect_same_surfaces(r.grow, grown);
    BoundPlaneConfig pc;
    pc.mu = config.grow.mu;
    const BoundPlanes planes = compute_bound_planes(cloud, grown.surfaces, grown.labels, pc);
    ASSERT_EQ(r.planes->planes.size(), planes.planes.size());
    EXPECT_EQ(r.planes->stats.area, planes.stats.area);
    expect_same_coverage(*r.coverage, plan_coverage(planes, grown.surfaces, CoverageConfig{}));
    // The grid on the grower's index is the grid rebuilt from the labels, as `occupancy` does.
    expect_same_grid(*r.occupancy, occupancy_grid(cloud, grown.labels, config.grow));
    EXPECT_EQ(r.collision->size(), CollisionSpheres::from_surfaces(grown.surfaces).size());
}

INSTANTIATE_TEST_SUITE_P(CropOrNot, PipelineStages, ::testing::Bool());

TEST(Pipeline, SameResultForAnyThreadCount) {
    const PointCloud cloud = scene_cloud();
    PipelineConfig one, two;
    one.grow.threads = 1;
    two.grow.threads = 2;
    const PipelineResult a = run_pipeline(cloud, one);
    const PipelineResult b = run_pipeline(cloud, two);
    expect_same_surfaces(a.grow, b.grow);
    expect_same_coverage(*a.coverage, *b.coverage);
    expect_same_grid(*a.occupancy, *b.occupancy);
}

// A caller whose points live in its own buffer (a sensor driver's, a numpy array's) runs the
// pipeline on a view of them: the same result as on a PointCloud copy, nothing copied in.
TEST(Pipeline, ReadsACloudViewOfTheCallersOwnBuffers) {
    const PointCloud cloud = scene_cloud();
    struct DriverFrame {  // not a PointCloud: the caller's own layout
        std::vector<float> xyz;
        std::vector<std::uint32_t> scan;
        std::vector<Vec3d> origins;
    } frame;
    for (const Vec3f& p : cloud.points) frame.xyz.insert(frame.xyz.end(), {p.x(), p.y(), p.z()});
    frame.scan.assign(cloud.size(), 0);
    frame.origins = {*cloud.viewpoint};
    static_assert(sizeof(Vec3f) == 3 * sizeof(float));

    CloudView view(
        std::span<const Vec3f>(reinterpret_cast<const Vec3f*>(frame.xyz.data()), cloud.size()));
    view.scan_index = frame.scan;
    view.scan_origins = frame.origins;
    PointCloud fused = cloud;  // the same scan as a one-scan fused cloud
    fused.viewpoint.reset();
    fused.scan_index = frame.scan;
    fused.scan_origins = frame.origins;

    const PipelineResult a = run_pipeline(view);
    const PipelineResult b = run_pipeline(fused);
    ASSERT_GT(a.grow.surfaces.size(), 50u);
    EXPECT_EQ(a.grow.stats.orientation, OrientationSource::kScanOrigins);
    expect_same_surfaces(a.grow, b.grow);
    ASSERT_EQ(a.planes->planes.size(), b.planes->planes.size());
    expect_same_coverage(*a.coverage, *b.coverage);
    expect_same_grid(*a.occupancy, *b.occupancy);
    // And the copy to_point_cloud makes of the view is the cloud it shows.
    const PointCloud copy = to_point_cloud(view);
    ASSERT_EQ(copy.size(), fused.size());  // bytes: the cloud holds a NaN point
    EXPECT_EQ(std::memcmp(copy.points.data(), fused.points.data(), fused.size() * sizeof(Vec3f)),
              0);
    EXPECT_EQ(copy.scan_index, fused.scan_index);
    EXPECT_EQ(copy.scan_origins, fused.scan_origins);
}

TEST(Pipeline, StagesNotAskedForAreEmpty) {
    const PointCloud cloud = scene_cloud();
    PipelineConfig config;
    config.planes.reset();  // coverage needs planes: off with them
    config.occupancy = false;
    config.collision = false;
    const PipelineResult r = run_pipeline(cloud, config);
    EXPECT_GT(r.grow.surfaces.size(), 0u);
    EXPECT_FALSE(r.planes || r.coverage || r.occupancy || r.collision);
    EXPECT_EQ(r.seconds.planes + r.seconds.coverage + r.seconds.occupancy + r.seconds.collision,
              0.0);
}

TEST(Pipeline, ConfigurationIsCheckedUpFrontAndTakesTheGrowersMuAndThreads) {
    PipelineConfig bad_grow;
    bad_grow.grow.mu = -1;
    EXPECT_THROW(Pipeline{bad_grow}, Error);
    PipelineConfig bad_coverage;
    bad_coverage.coverage->standoff = -0.1;
    try {
        const Pipeline p(bad_coverage);
        ADD_FAILURE() << "a negative standoff was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
    }
    PipelineConfig c;
    c.grow.mu = 0.02;
    c.grow.threads = 3;
    c.planes->mu = 7;
    const Pipeline p(c);
    EXPECT_EQ(p.config().planes->mu, 0.02);
    EXPECT_EQ(p.config().planes->threads, 3);
    EXPECT_EQ(p.config().coverage->threads, 3);
}

TEST(Pipeline, ReportsItsStagesInOrderEndingWithDone) {
    const PointCloud cloud = scene_cloud();
    PipelineConfig config;
    std::vector<std::string> heard;
    config.grow.progress = [&](std::string_view stage, double) {
        if (heard.empty() || heard.back() != stage) heard.emplace_back(stage);
    };
    (void)run_pipeline(cloud, config);
    ASSERT_GE(heard.size(), 5u);
    const std::vector<std::string> tail(heard.end() - 5, heard.end());
    EXPECT_EQ(tail,
              (std::vector<std::string>{"planes", "coverage", "occupancy", "collision", "done"}));
}

// finish() (a Map's path) builds the occupancy grid and the collision spheres while the planes
// run: the same outputs as run() gives, for any thread count.
TEST(Pipeline, FinishGivesWhatRunGivesForAnyThreadCount) {
    const PointCloud cloud = scene_cloud();
    for (const int threads : {1, 2, 3}) {
        PipelineConfig config;
        config.grow.threads = threads;
        const Pipeline pipeline(config);
        const PipelineResult whole = pipeline.run(cloud);
        const PipelineResult r = pipeline.finish(cloud, grow_surfaces(cloud, config.grow));
        expect_same_surfaces(r.grow, whole.grow);
        ASSERT_TRUE(r.planes && r.coverage && r.occupancy && r.collision);
        ASSERT_EQ(r.planes->planes.size(), whole.planes->planes.size());
        EXPECT_EQ(r.planes->stats.area, whole.planes->stats.area);
        expect_same_coverage(*r.coverage, *whole.coverage);
        expect_same_grid(*r.occupancy, *whole.occupancy);
        EXPECT_EQ(r.collision->size(), whole.collision->size());
    }
}

// A stage that throws while the grid is built beside it: the error reaches the caller, after
// the other thread is done with the result it was filling (ASan sees any use after that), and
// the grown result handed over is left as it was.
TEST(Pipeline, FinishReportsABadGrowResultWhileTheGridIsBuilt) {
    const PointCloud cloud = scene_cloud();
    PipelineConfig config;
    config.grow.threads = 2;
    const Pipeline pipeline(config);
    GrowResult grown = grow_surfaces(cloud, config.grow);
    GrowResult stray = grown;
    stray.labels[stray.labels.size() / 2] = static_cast<std::int32_t>(stray.surfaces.size());
    EXPECT_THROW((void)pipeline.finish(cloud, std::move(stray)), Error);
    // Handed over as an rvalue, the result is taken only once every stage has run: a map keeps
    // its grown surfaces and labels.
    EXPECT_EQ(stray.labels.size(), cloud.size());
    EXPECT_EQ(stray.surfaces.size(), grown.surfaces.size());
    grown.labels.pop_back();
    EXPECT_THROW((void)pipeline.finish(cloud, std::move(grown)), Error);
}

TEST(Pipeline, AnIndexOfAnotherCloudIsRefused) {
    const PointCloud cloud = scene_cloud();
    PointCloud other = cloud;
    other.points.resize(other.points.size() / 2);
    const SurfaceGrower grower{GrowerConfig{}};
    const GrowIndex index = grower.index(other);
    EXPECT_THROW((void)grower.grow(cloud, index), Error);
    // The index of the same cloud gives what grow(cloud) gives.
    expect_same_surfaces(grower.grow(cloud, grower.index(cloud)), grower.grow(cloud));
}

}  // namespace
}  // namespace surfgrow
