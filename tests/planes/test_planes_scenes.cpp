// Bound planes and coverage on simulated built-in scenes, scored against their ground truth.
//
// Each scene is scanned from 3 poses (seed 1), fused, grown with the defaults and merged with the
// defaults. Only planar faces are scored (a cylinder's side is cut into strips by design); faces
// and planes with fewer than 200 points are left out, and an overlap counts when it holds 5 % of
// the face (over-segmentation) or of the plane (under-segmentation) and 50 points. The bounds
// below are the measured values (docs/planes-and-coverage.md), so a change that makes
// segmentation worse fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "support/test_support.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/eval/segmentation_score.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/coverage.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace surfgrow {
namespace {

struct SceneRun {
    PointCloud cloud;  // labels: true planar face, -1 elsewhere
    GrowResult grown;
    BoundPlanes planes;
    eval::SegmentationScore faces;   // against the true faces
    eval::SegmentationScore pieces;  // against their connected pieces (24 mm link)
};

SceneRun run(const std::string& name, const GrowerConfig& grow = GrowerConfig{}) {
    const scanner::SceneDescription desc = scanner::builtin_scene(name);
    const scanner::Scene scene(desc);
    std::vector<scanner::RawScan> raws;
    for (scanner::SimulatedScan& s :
         scanner::ScanSimulator(scene).simulate(scanner::scan_poses(desc.scanner, 3), 1))
        raws.push_back(std::move(s.raw));
    SceneRun r;
    r.cloud = scanner::fuse_scans(raws);
    for (std::int32_t& l : r.cloud.labels)
        if (l >= 0 && !scene.faces()[static_cast<std::size_t>(l)].planar()) l = -1;
    r.grown = grow_surfaces(r.cloud, grow);
    r.planes = compute_bound_planes(r.cloud, r.grown, BoundPlaneConfig{});
    const auto found = plane_labels(r.planes, r.grown.labels);
    r.faces = eval::score_segmentation(r.cloud.labels, found);
    r.pieces =
        eval::score_segmentation(eval::truth_pieces(r.cloud.points, r.cloud.labels, 0.024), found);
    return r;
}

void check_coverage(const SceneRun& r, double min_coverage) {
    const CoveragePlan plan = plan_coverage(r.planes, r.grown, CoverageConfig{});
    EXPECT_GE(plan.stats.coverage, min_coverage);
    EXPECT_EQ(plan.stats.planes, r.planes.planes.size());  // every plane gets goals
    EXPECT_EQ(plan.stats.transitions, plan.stats.planes - 1);
    for (const CoverageGoal& g : plan.goals) {
        const double angle =
            std::atan2((-g.tool_axis).cross(g.normal).norm(), (-g.tool_axis).dot(g.normal)) * 180 /
            M_PI;
        ASSERT_GE(angle, 5.0 - 1e-9);
        ASSERT_LE(angle, 40.0 + 1e-9);
        ASSERT_NEAR((g.tool_position - g.position).norm(), 0.3, 1e-9);
    }
    // The large planes are covered nearly whole (measured >= 0.985: thin strips lose most).
    for (const PlaneCoverage& pc : plan.per_plane)
        if (pc.area > 0.05) {
            EXPECT_GE(pc.covered_fraction, 0.98) << "plane " << pc.plane;
        }
}

TEST(PlanesOnScenes, RoomCornerGivesOnePlanePerWall) {
    const SceneRun r = run("room-corner");
    // Measured: 3 faces, none split, none merged; 99.1 % of their points in their own plane.
    EXPECT_EQ(r.faces.faces, 3u);
    EXPECT_EQ(r.faces.over_segmented, 0u);
    EXPECT_EQ(r.faces.under_segmented, 0u);
    EXPECT_EQ(r.faces.one_to_one, 3u);
    EXPECT_GE(r.faces.points_in_best, 0.985);
    // The three largest planes are the floor and the walls, with their true normals (the walls,
    // of about the same size, in either order).
    ASSERT_GE(r.planes.planes.size(), 3u);
    for (const Vec3d& truth : {Vec3d(0, -1, 0), Vec3d(-1, 0, 0), Vec3d(0, 0, 1)}) {
        double best = M_PI;
        for (std::size_t k = 0; k < 3; ++k)
            best = std::min(best, angle_between(r.planes.planes[k].normal, truth));
        EXPECT_LT(best, 0.005) << truth.transpose();
    }
    for (std::size_t k = 0; k < 3; ++k)
        std::printf("plane %zu: %llu points, normal %.4f %.4f %.4f\n", k,
                    static_cast<unsigned long long>(r.planes.planes[k].point_count),
                    r.planes.planes[k].normal.x(), r.planes.planes[k].normal.y(),
                    r.planes.planes[k].normal.z());
    check_coverage(r, 0.998);  // measured 0.9990
}

// The paper's loop: eq. (2) at a fixed mu (no adaptive radius); the bounds below were measured
// on it.
GrowerConfig fixed_mu() {
    GrowerConfig c;
    c.plane_test = PlaneTest::kPaper;
    c.adaptive_factor = 1.0;
    c.pool_radius = 2 * c.mu;
    return c;
}

TEST(PlanesOnScenes, IBeamChannelSegmentsItsStructuralFaces) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const SceneRun r = run("ibeam-channel", fixed_mu());
    // Measured: 25 planar faces with 200+ points; 8 split (stiffener sides seen in bands with
    // 70-190 mm occlusion gaps, a top flange's 30 mm edge strip, one bolt head), 2 planes that
    // hold more than 5 % of a second face (the top flanges' edge strips with deck points from
    // the concave corner above them). Against connected pieces: 33 pieces, 3 split.
    EXPECT_EQ(r.faces.faces, 25u);
    EXPECT_LE(r.faces.over_segmented, 8u);
    EXPECT_LE(r.faces.under_segmented, 2u);
    EXPECT_GE(r.faces.one_to_one, 17u);
    EXPECT_LE(r.pieces.over_segmented, 3u);
    EXPECT_GE(r.faces.points_in_best, 0.97);  // measured 0.976 (pieces: 0.991)
    // The deck and both webs are the three largest planes, each almost purely its face.
    const auto found = plane_labels(r.planes, r.grown.labels);
    for (std::int32_t k = 0; k < 3; ++k) {
        std::map<std::int32_t, std::uint64_t> faces;
        std::uint64_t n = 0;
        for (std::size_t i = 0; i < found.size(); ++i)
            if (found[i] == k && r.cloud.labels[i] >= 0) {
                ++n;
                ++faces[r.cloud.labels[i]];
            }
        std::uint64_t best = 0;
        for (const auto& [face, count] : faces) best = std::max(best, count);
        EXPECT_GT(n, 100000u) << "plane " << k;
        EXPECT_GE(double(best), 0.99 * double(n)) << "plane " << k;
    }
    check_coverage(r, 0.997);  // measured 0.9982
}

// With grow's defaults (the disk test, adaptive radius up to 8 mu) the far, sparse faces register
// too: more faces are scored (27-28 with 200+ points, against 25), and those far faces split more
// and share their edge strips more often. Measured: 13 split, 8 planes holding 5 % of a second
// face, 15 one-to-one; against pieces 8 split. The near faces and the three largest planes are as
// good.
TEST(PlanesOnScenes, IBeamChannelWithTheDefaultAdaptiveRadius) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const SceneRun r = run("ibeam-channel");
    // Faces with 200+ registered points: 27-28 (a 30 mm flange edge strip that the disk test
    // leaves out rather than give to the deck beside it may fall below 200).
    EXPECT_GE(r.faces.faces, 27u);
    EXPECT_LE(r.faces.over_segmented, 13u);
    EXPECT_LE(r.faces.under_segmented, 8u);
    EXPECT_GE(r.faces.one_to_one, 15u);
    EXPECT_LE(r.pieces.over_segmented, 8u);
    check_coverage(r, 0.99);
}

TEST(PlanesOnScenes, SameResultForAnyThreadCount) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    SceneRun r = run("room-corner");
    BoundPlaneConfig cfg;
    cfg.threads = 1;
    const BoundPlanes one = compute_bound_planes(r.cloud, r.grown, cfg);
    cfg.threads = 3;
    const BoundPlanes three = compute_bound_planes(r.cloud, r.grown, cfg);
    EXPECT_EQ(one.plane_of_patch, three.plane_of_patch);
    ASSERT_EQ(one.planes.size(), three.planes.size());
    for (std::size_t k = 0; k < one.planes.size(); ++k) {
        EXPECT_EQ(one.planes[k].area, three.planes[k].area);
        EXPECT_EQ(one.planes[k].normal, three.planes[k].normal);
    }
}

}  // namespace
}  // namespace surfgrow
