// Mapping scan by scan against growing the fused cloud at once: the same cloud, registration,
// normal error (median, p95 and the share far off), bound planes and faces found within the
// bounds docs/scanner.md states; deterministic for any number of threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/pipeline/map.hpp"
#include "surfgrow/planes/bound_plane_memo.hpp"
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

void expect_same_planes(const BoundPlanes& a, const BoundPlanes& b) {
    ASSERT_EQ(a.planes.size(), b.planes.size());
    EXPECT_EQ(a.plane_of_patch, b.plane_of_patch);
    EXPECT_EQ(a.stats.adjacent_pairs, b.stats.adjacent_pairs);
    EXPECT_EQ(a.stats.area, b.stats.area);
    for (std::size_t k = 0; k < a.planes.size(); ++k) {
        const BoundPlane &p = a.planes[k], &q = b.planes[k];
        EXPECT_EQ(p.patches, q.patches) << "plane " << k;
        EXPECT_TRUE(p.normal == q.normal && p.centroid == q.centroid && p.u_axis == q.u_axis &&
                    p.area == q.area && p.rms == q.rms && p.degenerate == q.degenerate)
            << "plane " << k;
        ASSERT_EQ(p.polygons.size(), q.polygons.size()) << "plane " << k;
        for (std::size_t i = 0; i < p.polygons.size(); ++i)
            EXPECT_TRUE(p.polygons[i].outer == q.polygons[i].outer &&
                        p.polygons[i].holes == q.polygons[i].holes)
                << "plane " << k;
    }
}

void expect_same_coverage(const CoveragePlan& a, const CoveragePlan& b) {
    ASSERT_EQ(a.goals.size(), b.goals.size());
    for (std::size_t k = 0; k < a.goals.size(); ++k)
        EXPECT_TRUE(a.goals[k].plane == b.goals[k].plane &&
                    a.goals[k].position == b.goals[k].position &&
                    a.goals[k].tool_position == b.goals[k].tool_position &&
                    a.goals[k].orientation.coeffs() == b.goals[k].orientation.coeffs())
            << "goal " << k;
    ASSERT_EQ(a.per_plane.size(), b.per_plane.size());
    for (std::size_t k = 0; k < a.per_plane.size(); ++k)
        EXPECT_EQ(a.per_plane[k].covered_fraction, b.per_plane[k].covered_fraction);
    EXPECT_EQ(a.stats.tool_path_length, b.stats.tool_path_length);
}

// A map's planes against those fitted anew on the same patches (docs/scanner.md, "Mapping
// while scanning"): where a region gained points the map traces its boundary on the cell counts
// it kept (detail::extend_region) instead of a raster of all its points. The plane itself
// (normal, centroid, RMS, box) is the same; its rasters lie on another lattice (the frame of its
// last fit anew), so a cell's width of the boundary may fall either way: the largest difference
// of area, over the perimeter times the raster cell, is returned. Counts the planes whose frame
// or area differ in `extended`.
double boundary_cells_apart(const BoundPlanes& got, const BoundPlanes& truth,
                            std::size_t& extended) {
    EXPECT_EQ(got.plane_of_patch, truth.plane_of_patch);
    EXPECT_EQ(got.stats.adjacent_pairs, truth.stats.adjacent_pairs);
    EXPECT_EQ(got.planes.size(), truth.planes.size());
    double worst = 0;
    for (std::size_t k = 0; k < std::min(got.planes.size(), truth.planes.size()); ++k) {
        const BoundPlane &p = got.planes[k], &q = truth.planes[k];
        EXPECT_EQ(p.patches, q.patches) << "plane " << k;
        EXPECT_TRUE(p.normal == q.normal && p.centroid == q.centroid && p.rms == q.rms &&
                    p.point_count == q.point_count && p.degenerate == q.degenerate &&
                    p.bounds.min == q.bounds.min && p.bounds.max == q.bounds.max &&
                    p.closing_radius == q.closing_radius)
            << "plane " << k;
        EXPECT_NEAR(p.u_axis.dot(p.normal), 0.0, 1e-12) << "plane " << k;
        EXPECT_NEAR(p.v_axis.dot(p.u_axis), 0.0, 1e-12) << "plane " << k;
        extended += p.u_axis != q.u_axis || p.area != q.area;
        const double perimeter = test::boundary_length(q.polygons);
        if (perimeter > 0)
            worst =
                std::max(worst, std::abs(p.area - q.area) / (perimeter * truth.config.resolution));
    }
    return worst;
}

TEST_F(MapTest, OutputsAfterEachScanAreThoseComputedAnewWithinBounds) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    // The map carries the planes' and coverage's work over to the next scan (PipelineMemo):
    // where a region is the same, its plane and goals are the ones computed anew, bit for bit;
    // where it gained points, its plane is extended within the bounds below. A memo whose
    // planes and goals are marked shows which were taken as they were.
    MapConfig c;
    c.pipeline.occupancy = c.pipeline.collision = false;
    Map map(c);
    const Pipeline anew(c.pipeline);
    PipelineMemo marked;
    std::size_t extended = 0;
    for (std::size_t k = 0; k < scans_->size(); ++k) {
        const scanner::RawScan& raw = (*scans_)[k];
        const PointCloud one = scanner::fuse_scans(std::span(&raw, 1));
        const PipelineResult& r = map.add_scan(one, raw.pose.translation());
        const PipelineResult truth = anew.finish(map.cloud(), r.grow);
        SCOPED_TRACE("after scan " + std::to_string(k));
        std::size_t now = 0;
        const double cells = boundary_cells_apart(*r.planes, *truth.planes, now);
        const CoveragePlan &got = *r.coverage, &want = *truth.coverage;
        std::printf(
            "after scan %zu: %zu of %zu planes traced on their counts, area %.3f boundary cells "
            "apart; goals %zu / %zu, coverage %.4f / %.4f\n",
            k, now, r.planes->planes.size(), cells, got.goals.size(), want.goals.size(),
            got.stats.coverage, want.stats.coverage);
        extended += now;
        EXPECT_LE(cells, 1.0);
        EXPECT_NEAR(double(got.goals.size()), double(want.goals.size()),
                    0.01 * double(want.goals.size()));
        EXPECT_NEAR(got.stats.coverage, want.stats.coverage, 0.005);
        if (k == 0) {  // the first scan's planes are all fitted anew
            EXPECT_EQ(now, 0u);
            expect_same_coverage(got, want);
        }

        const PipelineResult recalled = anew.finish(map.cloud(), r.grow, &marked);
        std::size_t planes = 0, goals = 0;
        for (const BoundPlane& p : recalled.planes->planes) planes += p.rms < 0;
        for (const PlaneCoverage& p : recalled.coverage->per_plane) goals += p.covered_fraction < 0;
        std::printf("after scan %zu: %zu of %zu planes and %zu of %zu planes' goals recalled\n", k,
                    planes, recalled.planes->planes.size(), goals,
                    recalled.coverage->per_plane.size());
        if (k > 0) {  // more as the map grows: after the third scan, 32 of 124
            EXPECT_GT(planes * (k == 1 ? 20 : 5), recalled.planes->planes.size());
            EXPECT_GT(goals * (k == 1 ? 20 : 5), recalled.coverage->per_plane.size());
        }
        for (FittedRegion& f : marked.planes.regions) f.plane.rms = -1;
        for (CoverageMemo::Plane& p : marked.coverage.planes) p.goals.covered_fraction = -1;
    }
    EXPECT_GT(extended, 0u);  // else the bounds above were never put to the test
    // The bound planes' memo of other patches (the whole map's, given the first scan's map) is
    // not used: no marked plane comes out. (Coverage's is keyed by each plane's contents: a
    // plane the same in both may take its goals.)
    Map first(c);
    const scanner::RawScan& raw = (*scans_)[0];
    const PipelineResult& r0 =
        first.add_scan(scanner::fuse_scans(std::span(&raw, 1)), raw.pose.translation());
    expect_same_planes(*anew.finish(first.cloud(), r0.grow, &marked).planes, *r0.planes);
}

TEST_F(MapTest, OccupancyAfterEachScanIsTheGridBuiltAnew) {
    // The map extends its occupancy grid by each scan's registered points where the scan leaves
    // the grown points' low corner (the grid's origin) where it was, else indexes its cloud
    // anew (OccupancyMemo): after every scan the grid must be the one built anew. A memo whose
    // grid is marked (cube 0, never occupied: the origin lies a cube and a half below the
    // lowest point) shows where it was extended. The three scans each reach lower than the one
    // before (by millimetres of noise on the floor); the first scan taken again cannot.
    MapConfig c;
    c.pipeline.planes.reset();
    c.pipeline.coverage.reset();
    c.pipeline.collision = false;
    Map map(c);
    const Pipeline anew(c.pipeline);
    PipelineMemo marked;
    std::size_t extended = 0;
    for (std::size_t k = 0; k <= scans_->size(); ++k) {
        const scanner::RawScan& raw = (*scans_)[k % scans_->size()];
        const PipelineResult& r =
            map.add_scan(scanner::fuse_scans(std::span(&raw, 1)), raw.pose.translation());
        const OccupancyGrid truth = *anew.finish(map.cloud(), r.grow).occupancy;
        SCOPED_TRACE("after scan " + std::to_string(k));
        const OccupancyGrid& got = *r.occupancy;
        EXPECT_FALSE(got.occupied_cell(CellCoords::Zero()));
        EXPECT_EQ(got.origin(), truth.origin());
        EXPECT_EQ(got.registered_points(), truth.registered_points());
        ASSERT_EQ(got.size(), truth.size());
        EXPECT_TRUE(std::equal(got.cells().begin(), got.cells().end(), truth.cells().begin()));
        EXPECT_TRUE(std::equal(got.point_counts().begin(), got.point_counts().end(),
                               truth.point_counts().begin()));

        extended +=
            anew.finish(map.cloud(), r.grow, &marked).occupancy->occupied_cell(CellCoords::Zero());
        marked.occupancy.grid->add_registered({CellCoords::Zero()});
    }
    std::printf("the grid extended after %zu of %zu scans\n", extended, scans_->size() + 1);
    EXPECT_GE(extended, 1u);
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
