// Mapping scan by scan against growing the fused cloud at once: the same cloud, registration,
// normal error (median, p95 and the share far off), bound planes and faces found within the
// bounds docs/scanner.md states; deterministic for any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/pipeline/map.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace surfgrow {
namespace {

eval::EvalReport score(const CloudView& cloud, const PipelineResult& r,
                       const scanner::Scene& scene) {
    eval::EvalReport e = eval::evaluate(cloud, r.grow, scene.faces());
    const eval::GrowOutcome grown{r.grow.surfaces, r.grow.labels, &r.grow.stats};
    eval::add_plane_figures(e, cloud, grown, *r.planes, scene.faces());
    return e;
}

class MapTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        scene_ = new scanner::Scene(scanner::ibeam_channel_scene());
        scans_ = new std::vector<scanner::RawScan>();
        const auto poses = scanner::scan_poses(scene_->description().scanner, 3);
        for (scanner::SimulatedScan& s : scanner::ScanSimulator(*scene_).simulate(poses, 11))
            scans_->push_back(std::move(s.raw));
    }
    static void TearDownTestSuite() {
        delete scans_;
        delete scene_;
    }
    static Map map_of(int threads, bool everything = true, std::size_t scans = 3) {
        MapConfig c;
        c.pipeline.grow.threads = threads;
        c.pipeline.occupancy = c.pipeline.collision = everything;
        Map map(c);
        for (std::size_t k = 0; k < scans; ++k) {
            const scanner::RawScan& raw = (*scans_)[k];
            const PointCloud one = scanner::fuse_scans(std::span(&raw, 1));
            (void)map.add_scan(one, raw.pose.translation());
        }
        return map;
    }
    static scanner::Scene* scene_;
    static std::vector<scanner::RawScan>* scans_;
};
scanner::Scene* MapTest::scene_ = nullptr;
std::vector<scanner::RawScan>* MapTest::scans_ = nullptr;

TEST_F(MapTest, ScanByScanIsAsGoodAsTheFusedCloudAtOnce) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const Map map = map_of(0);
    const PointCloud fused = scanner::fuse_scans(*scans_);
    // The map's cloud is the fused cloud, point for point.
    ASSERT_EQ(map.cloud().points, fused.points);
    EXPECT_EQ(map.cloud().scan_index, fused.scan_index);
    EXPECT_EQ(map.cloud().labels, fused.labels);
    EXPECT_EQ(map.scans(), 3u);
    // Later scans mostly join what the first grew; nothing grown before is grown again.
    EXPECT_GT(map.last_update().joined, map.last_update().points / 3);

    const PipelineResult batch = run_pipeline(fused);
    const eval::EvalReport m = score(map.cloud(), map.result(), *scene_);
    const eval::EvalReport b = score(fused, batch, *scene_);
    std::printf(
        "map / batch: planar registered %.4f / %.4f, normal median %.3f / %.3f, p95 %.3f / "
        "%.3f, over 45 %.4f / %.4f, planes p95 %.3f / %.3f, faces %llu / %llu of %llu, "
        "purity %.4f / %.4f\n",
        m.planar.fraction(), b.planar.fraction(), m.normal_deg.median, b.normal_deg.median,
        m.normal_deg.p95, b.normal_deg.p95, m.normal_over_45, b.normal_over_45,
        m.planes.normal_deg.p95, b.planes.normal_deg.p95,
        static_cast<unsigned long long>(m.planes.faces_detected),
        static_cast<unsigned long long>(b.planes.faces_detected),
        static_cast<unsigned long long>(b.planes.faces_scored), m.purity, b.purity);
    // The bounds of docs/scanner.md, "Mapping while scanning".
    EXPECT_GE(m.planar.fraction(), b.planar.fraction() - 0.01);
    EXPECT_GE(m.planar.fraction(), 0.98);
    EXPECT_LE(m.normal_deg.median, b.normal_deg.median + 0.2);
    EXPECT_LE(m.normal_deg.p95, b.normal_deg.p95 + 1.5);
    EXPECT_LE(m.normal_over_45, b.normal_over_45 + 0.005);
    EXPECT_LE(m.planes.normal_deg.p95, b.planes.normal_deg.p95 + 1.0);
    EXPECT_GE(m.planes.faces_detected + 2, b.planes.faces_detected);
    EXPECT_GE(m.purity, b.purity - 0.01);
    EXPECT_GE(m.facing_sensor.fraction(), 0.99);
    // Every output of the pipeline is there, for the whole map.
    ASSERT_TRUE(map.result().planes && map.result().coverage && map.result().occupancy &&
                map.result().collision);
    EXPECT_EQ(map.result().collision->spheres().size(), map.result().grow.surfaces.size());
}

TEST_F(MapTest, TheSameForAnyNumberOfThreads) {
    // Two scans: the second joins and grows, which is all a third would do.
    const Map one = map_of(1, false, 2), two = map_of(2, false, 2);
    EXPECT_EQ(one.result().grow.labels, two.result().grow.labels);
    ASSERT_EQ(one.result().grow.surfaces.size(), two.result().grow.surfaces.size());
    for (std::size_t s = 0; s < one.result().grow.surfaces.size(); ++s) {
        EXPECT_EQ(one.result().grow.surfaces[s].normal, two.result().grow.surfaces[s].normal);
        EXPECT_EQ(one.result().grow.surfaces[s].point_count,
                  two.result().grow.surfaces[s].point_count);
    }
    EXPECT_EQ(one.result().planes->plane_of_patch, two.result().planes->plane_of_patch);
}

TEST(Map, RefusesWhatItCannotUse) {
    MapConfig c;
    c.join_tolerance = 0.5;
    EXPECT_THROW(Map{c}, Error);
    Map map{MapConfig{}};
    const PointCloud empty;
    EXPECT_THROW((void)map.add_scan(empty, Vec3d(NAN, 0, 0)), Error);
    // An empty scan is a scan: nothing joins, nothing grows.
    EXPECT_NO_THROW((void)map.add_scan(empty, Vec3d::Zero()));
    EXPECT_EQ(map.scans(), 1u);
    EXPECT_TRUE(map.result().grow.surfaces.empty());
}

}  // namespace
}  // namespace surfgrow
