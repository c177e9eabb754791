// The evaluation's metrics on hand-made clouds and results with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::eval {
namespace {

using scanner::Cylinder;
using scanner::Rectangle;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Faces 0: floor z = 0 (normal +z); 1: wall x = 1 (normal +x); 2: an open cylinder's side along
// z through (0.5, 0.5), radius 0.1.
std::vector<scanner::Face> test_faces() {
    scanner::SceneDescription d;
    d.primitives.push_back(
        {"floor", Rectangle{Vec3d(0, 0, 0), Vec3d::UnitX(), Vec3d::UnitY(), 1, 1}});
    d.primitives.push_back(
        {"wall", Rectangle{Vec3d(1, 0, 0.5), Vec3d::UnitY(), Vec3d::UnitZ(), 1, 1}});
    d.primitives.push_back(
        {"pipe", Cylinder{Vec3d(0.5, 0.5, 0), Vec3d(0.5, 0.5, 0.5), 0.1, false}});
    return scanner::Scene(d).faces();
}

Surface surface(const Vec3d& normal, const Vec3d& centroid) {
    Surface s;
    s.normal = normal.normalized();
    s.centroid = centroid;
    s.home = centroid;
    return s;
}

// 100 floor points (label 0), 100 wall points (1), 20 points on the pipe's side facing +x (2),
// 10 points 1 mm above the floor on no face (-1), 2 NaN points; viewpoint (0, 0, 1).
struct Case {
    PointCloud cloud;
    std::vector<Surface> surfaces;
    std::vector<std::int32_t> labels;  // surface per point
    void add(const Vec3d& p, std::int32_t truth, std::int32_t surface) {
        cloud.points.push_back(p.cast<float>());
        cloud.labels.push_back(truth);
        labels.push_back(surface);
    }
};

Case base_case() {
    Case c;
    c.cloud.viewpoint = Vec3d(0, 0, 1);
    c.surfaces = {surface(Vec3d::UnitZ(), Vec3d::Zero()),
                  surface(-Vec3d::UnitX(), Vec3d(1, 0, 0.5)),
                  surface(Vec3d::UnitX(), Vec3d(0.6, 0.5, 0.25))};
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) c.add(Vec3d(0.1 * i - 0.45, 0.1 * j - 0.45, 0), 0, 0);
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) c.add(Vec3d(1, 0.1 * i - 0.45, 0.05 * j + 0.5), 1, 1);
    for (int i = 0; i < 20; ++i) c.add(Vec3d(0.6, 0.5, 0.02 * i + 0.05), 2, 2);
    for (int i = 0; i < 10; ++i) c.add(Vec3d(0.05 * i, -0.2, 0.001), -1, 0);
    const float nan = std::nanf("");
    for (int i = 0; i < 2; ++i) {
        c.cloud.points.emplace_back(nan, nan, nan);
        c.cloud.labels.push_back(0);
        c.labels.push_back(-1);
    }
    return c;
}

EvalReport run(const Case& c, const EvalOptions& o = {}, const GrowStats* stats = nullptr) {
    const std::vector<scanner::Face> faces = test_faces();
    return evaluate(c.cloud, GrowOutcome{c.surfaces, c.labels, stats}, faces, o);
}

TEST(Evaluation, PerfectResultGivesExactFigures) {
    const EvalReport r = run(base_case());
    EXPECT_EQ(r.points, 232u);
    EXPECT_EQ(r.finite_points, 230u);
    EXPECT_EQ(r.all.points, 230u);
    EXPECT_DOUBLE_EQ(r.all.fraction(), 1.0);
    EXPECT_EQ(r.planar.points, 200u);
    EXPECT_EQ(r.curved.points, 20u);
    EXPECT_EQ(r.unlabelled.points, 10u);
    EXPECT_EQ(r.unlabelled_members, 10u);
    EXPECT_EQ(r.normal_deg.count, 200u);
    EXPECT_NEAR(r.normal_deg.median, 0.0, 1e-9);
    EXPECT_NEAR(r.normal_deg.max, 0.0, 1e-9);
    EXPECT_EQ(r.normal_curved_deg.count, 20u);
    EXPECT_NEAR(r.normal_curved_deg.max, 0.0, 1e-6);  // radial normal +x where the points are
    EXPECT_DOUBLE_EQ(r.purity, 1.0);
    EXPECT_DOUBLE_EQ(r.purity_surface_mean, 1.0);
    EXPECT_EQ(r.impure_surfaces, 0u);
    // Only the points 1 mm above the floor are off their plane (up to float rounding).
    EXPECT_NEAR(r.residual_m.mean, 10 * 0.001 / 230.0, 1e-8);
    EXPECT_NEAR(r.residual_m.max, 0.001, 1e-9);
    EXPECT_EQ(r.faces_with_points, 3u);
    EXPECT_EQ(r.faces_grown, 3u);
    EXPECT_EQ(r.faces_missed, 0u);
    EXPECT_DOUBLE_EQ(r.surfaces_per_face, 1.0);
    EXPECT_DOUBLE_EQ(r.data_reduction, 230.0 / 3.0);
    EXPECT_EQ(r.surface_normal_deg.count, 2u);  // the planar majority faces
    EXPECT_NEAR(r.plane_offset_m.max, 0.0, 1e-12);
    EXPECT_TRUE(std::isnan(r.registered_grown));  // no GrowStats given
    // Facing: floor (+z, sensor above) and wall (-x, sensor at x = 0) right; the pipe's surface
    // points +x, away from the sensor at x = 0: 20 of 220 wrong.
    EXPECT_EQ(r.facing_sensor.points, 220u);
    EXPECT_EQ(r.facing_sensor.registered, 200u);
}

TEST(Evaluation, ATiltedSurfaceShowsItsTiltAsTheNormalError) {
    Case c = base_case();
    c.surfaces[0].normal = Vec3d(0, std::sin(10 * kDeg), std::cos(10 * kDeg));
    const EvalReport r = run(c);
    // 100 floor points at 10 deg, 100 wall points at 0: median between, p95 and max 10.
    EXPECT_NEAR(r.normal_deg.median, 5.0, 1e-9);
    EXPECT_NEAR(r.normal_deg.p95, 10.0, 1e-9);
    EXPECT_NEAR(r.normal_deg.mean, 5.0, 1e-9);
    EXPECT_NEAR(r.surface_normal_deg.max, 10.0, 1e-9);
}

TEST(Evaluation, TheTailIsTheShareOfPointsBeyond10And45Degrees) {
    Case c = base_case();
    c.surfaces[0].normal = Vec3d(0, std::sin(20 * kDeg), std::cos(20 * kDeg));   // floor 20 off
    c.surfaces[1].normal = Vec3d(-std::cos(60 * kDeg), std::sin(60 * kDeg), 0);  // wall 60 off
    const EvalReport r = run(c);
    EXPECT_DOUBLE_EQ(r.normal_over_10, 1.0);
    EXPECT_DOUBLE_EQ(r.normal_over_45, 0.5);
    // By range band from the viewpoint (0, 0, 1): the floor lies 1.0-1.3 m, the wall 1.1-1.6 m.
    std::uint64_t counted = 0;
    for (const BandReport& b : r.bands) {
        if (b.normal_deg.count == 0) continue;
        counted += b.normal_deg.count;
        EXPECT_NEAR(b.over_10, 1.0, 1e-12);
        EXPECT_GE(b.over_45, 0.0);
        EXPECT_LE(b.over_45, 1.0);
    }
    EXPECT_EQ(counted, 200u);
    // By incidence: every planar point is in one 15-degree band, the floor's from 0 to 45
    // degrees (the viewpoint 1 m above its middle, its corners 0.64 m away), the wall's
    // beyond 45 (seen from x = 0, 1 m away in x, up to 0.45 m aside).
    ASSERT_EQ(r.incidence.size(), 6u);
    std::uint64_t planar = 0;
    for (const IncidenceReport& b : r.incidence) planar += b.planar.points;
    EXPECT_EQ(planar, 200u);
    EXPECT_DOUBLE_EQ(share_above(std::vector<double>{1, 20, 50}, 10), 2.0 / 3.0);
    EXPECT_TRUE(std::isnan(share_above(std::vector<double>{}, 10)));
}

TEST(Evaluation, TheWorstBandIsTheLowestRegisteredShareOfTheBandsThatCount) {
    Case c = base_case();
    for (int k = 100; k < 150; ++k) c.labels[static_cast<std::size_t>(k)] = -1;  // half the wall
    const EvalReport r = run(c);
    const double worst = r.worst_band_planar(10);
    EXPECT_LT(worst, 1.0);
    EXPECT_GT(worst, 0.0);
    for (const BandReport& b : r.bands) {
        if (b.planar.points < 10) continue;
        EXPECT_GE(b.planar.fraction(), worst);
    }
    EXPECT_TRUE(std::isnan(r.worst_band_planar(1000)));  // no band holds 1000
}

TEST(Evaluation, NormalsAreComparedAsLinesButOrientationIsCheckedToo) {
    Case c = base_case();
    for (Surface& s : c.surfaces) s.normal = -s.normal;
    const EvalReport r = run(c);
    EXPECT_NEAR(r.normal_deg.max, 0.0, 1e-9);    // sign-agnostic
    EXPECT_EQ(r.facing_sensor.registered, 20u);  // now only the pipe faces its sensor
}

TEST(Evaluation, UnregisteredPointsCountByKind) {
    Case c = base_case();
    for (std::size_t i = 0; i < 100; i += 2) c.labels[i] = -1;  // half the floor
    for (std::size_t i = 200; i < 205; ++i) c.labels[i] = -1;   // 5 of 20 on the pipe
    const EvalReport r = run(c);
    EXPECT_EQ(r.planar.registered, 150u);
    EXPECT_DOUBLE_EQ(r.planar.fraction(), 0.75);
    EXPECT_DOUBLE_EQ(r.curved.fraction(), 0.75);
    EXPECT_DOUBLE_EQ(r.all.fraction(), 175.0 / 230.0);
    EXPECT_EQ(r.faces[0].points.registered, 50u);
}

TEST(Evaluation, PurityIsTheMajorityFacesShare) {
    Case c = base_case();
    // Surface 0 takes 30 floor points and 10 wall points; the other 60 wall points stay on 1.
    for (std::size_t i = 30; i < 100; ++i) c.labels[i] = -1;
    for (std::size_t i = 100; i < 110; ++i) c.labels[i] = 0;
    for (std::size_t i = 110; i < 170; ++i) c.labels[i] = 1;
    for (std::size_t i = 170; i < 230; ++i) c.labels[i] = -1;
    const EvalReport r = run(c);
    EXPECT_DOUBLE_EQ(r.purity, 90.0 / 100.0);
    EXPECT_DOUBLE_EQ(r.purity_surface_mean, (0.75 + 1.0) / 2.0);
    EXPECT_EQ(r.impure_surfaces, 1u);
    EXPECT_EQ(r.faces[0].surfaces, 1u);
    EXPECT_EQ(r.faces[1].surfaces, 1u);
    EXPECT_EQ(r.faces[2].surfaces, 0u);
    EXPECT_EQ(r.faces_missed, 0u);  // the pipe has only 20 points, fewer than min_face_points
    EvalOptions strict;
    strict.min_face_points = 20;
    EXPECT_EQ(run(c, strict).faces_missed, 1u);
    // The wall points on the floor's surface are 90 deg off.
    EXPECT_NEAR(r.normal_deg.max, 90.0, 1e-9);
}

TEST(Evaluation, RangeBandsAndWorkspaceFromEachPointsOwnScan) {
    Case c;
    c.surfaces = {surface(Vec3d::UnitZ(), Vec3d::Zero())};
    c.cloud.scan_origins = {Vec3d(0, 0, 0.3), Vec3d(0, 0, 1.2)};
    // Scan 0 sees (0, 0, 0) at 0.3 m and (0.4, 0, 0) at 0.5 m; scan 1 sees (0, 0, 0) at 1.2 m.
    c.add(Vec3d(0, 0, 0), 0, 0);
    c.cloud.scan_index.push_back(0);
    c.add(Vec3d(0.4, 0, 0), 0, -1);
    c.cloud.scan_index.push_back(0);
    c.add(Vec3d(0, 0, 0), 0, 0);
    c.cloud.scan_index.push_back(1);
    EvalOptions o;
    o.band_m = 0.5;
    o.workspace_m = 1.0;
    const EvalReport r = run(c, o);
    ASSERT_TRUE(r.range_known);
    ASSERT_EQ(r.bands.size(), 3u);
    EXPECT_EQ(r.bands[0].all.points, 1u);  // 0.3 m
    EXPECT_EQ(r.bands[1].all.points, 1u);  // 0.5 m
    EXPECT_EQ(r.bands[1].all.registered, 0u);
    EXPECT_EQ(r.bands[2].all.points, 1u);  // 1.2 m
    EXPECT_DOUBLE_EQ(r.bands[2].from_m, 1.0);
    EXPECT_DOUBLE_EQ(r.bands[2].to_m, 1.5);
    EXPECT_EQ(r.planar_workspace.points, 2u);
    EXPECT_EQ(r.planar_workspace.registered, 1u);
    EXPECT_EQ(r.facing_sensor.registered, 2u);
}

TEST(Evaluation, WithoutAnyOriginThereAreNoBandsAndNoFacingCheck) {
    Case c = base_case();
    c.cloud.viewpoint.reset();
    const EvalReport r = run(c);
    EXPECT_FALSE(r.range_known);
    EXPECT_TRUE(r.bands.empty());
    EXPECT_EQ(r.facing_sensor.points, 0u);
    EXPECT_TRUE(std::isnan(r.facing_sensor.fraction()));
    EXPECT_TRUE(std::isnan(r.planar_workspace.fraction()));
}

TEST(Evaluation, AnOffsetCloudIsComparedInWorldCoordinates) {
    Case c = base_case();
    const Vec3d offset(50000, 60000, 100);  // scenes stay within 1e6 m
    c.cloud.offset = offset;
    c.cloud.viewpoint = Vec3d(0, 0, 1);
    // The same scene, moved to the georeferenced position; points and surfaces stay relative.
    scanner::SceneDescription d;
    d.primitives.push_back({"floor", Rectangle{offset, Vec3d::UnitX(), Vec3d::UnitY(), 1, 1}});
    d.primitives.push_back(
        {"wall", Rectangle{offset + Vec3d(1, 0, 0.5), Vec3d::UnitY(), Vec3d::UnitZ(), 1, 1}});
    d.primitives.push_back(
        {"pipe", Cylinder{offset + Vec3d(0.5, 0.5, 0), offset + Vec3d(0.5, 0.5, 0.5), 0.1, false}});
    const std::vector<scanner::Face> faces = scanner::Scene(d).faces();
    const EvalReport r = evaluate(c.cloud, GrowOutcome{c.surfaces, c.labels}, faces);
    EXPECT_NEAR(r.normal_curved_deg.max, 0.0, 1e-6);
    EXPECT_NEAR(r.plane_offset_m.max, 0.0, 1e-6);
}

TEST(Evaluation, RegisteredGrownComesFromTheGrowStats) {
    GrowStats stats;
    stats.valid_points = 200;
    stats.registered = 190;
    stats.registered_grown = 150;
    const EvalReport r = run(base_case(), {}, &stats);
    EXPECT_DOUBLE_EQ(r.registered_grown, 0.75);
    EXPECT_DOUBLE_EQ(r.registered_reported, 0.95);
}

TEST(Evaluation, InputsThatDoNotBelongTogetherAreRefused) {
    const std::vector<scanner::Face> faces = test_faces();
    auto expect_refused = [&](const Case& c) {
        try {
            (void)evaluate(c.cloud, GrowOutcome{c.surfaces, c.labels}, faces);
            ADD_FAILURE() << "no error";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << e.what();
        }
    };
    Case fewer_labels = base_case();
    fewer_labels.labels.pop_back();
    expect_refused(fewer_labels);
    Case no_truth = base_case();
    no_truth.cloud.labels.clear();
    expect_refused(no_truth);
    Case unknown_face = base_case();
    unknown_face.cloud.labels[3] = 3;
    expect_refused(unknown_face);
    Case unknown_surface = base_case();
    unknown_surface.labels[3] = 3;
    expect_refused(unknown_surface);
    Case bad_options = base_case();
    EvalOptions o;
    o.band_m = 0;
    EXPECT_THROW((void)evaluate(bad_options.cloud,
                                GrowOutcome{bad_options.surfaces, bad_options.labels}, faces, o),
                 Error);
}

TEST(Evaluation, AnEmptyCloudIsNotAnError) {
    const std::vector<scanner::Face> faces = test_faces();
    const PointCloud cloud;
    const EvalReport r = evaluate(cloud, GrowOutcome{}, faces);
    EXPECT_EQ(r.points, 0u);
    EXPECT_TRUE(std::isnan(r.all.fraction()));
    EXPECT_TRUE(std::isnan(r.normal_deg.median));
}

}  // namespace
}  // namespace surfgrow::eval
