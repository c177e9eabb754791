// Accuracy bounds on the built-in scenes at the datasheet noise, with the laser on and off the tilt
// axis, one scan and fused scans with pose errors; and a wrong result is caught.
// The figures measured with these settings are in docs/evaluation.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <tuple>

#include "support/test_support.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/eval/report_text.hpp"
#include "surfgrow/eval/requirement.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace surfgrow::eval {
namespace {

// Three scans along each scene's scan path, seed 1, the datasheet's noise (NoiseModel{}).
struct Scanned {
    std::unique_ptr<scanner::Scene> scene;
    PointCloud cloud;
};

const Scanned& scanned(const std::string& name) {
    static std::map<std::string, Scanned> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    Scanned s;
    s.scene = std::make_unique<scanner::Scene>(scanner::builtin_scene(name));
    const auto poses = scanner::scan_poses(s.scene->description().scanner, 3);
    std::vector<scanner::RawScan> raws;
    for (auto& sim : scanner::ScanSimulator(*s.scene).simulate(poses, 1))
        raws.push_back(std::move(sim.raw));
    s.cloud = scanner::fuse_scans(raws);
    return cache.emplace(name, std::move(s)).first->second;
}

struct Grown {
    GrowResult result;
    EvalReport report;
};

Grown grow_and_evaluate(const PointCloud& cloud, const scanner::Scene& scene,
                        const std::string& name, const GrowerConfig& config) {
    Grown g;
    g.result = grow_surfaces(cloud, config);
    g.report = evaluate(cloud, g.result, scene.faces());
    BoundPlaneConfig pc;
    pc.mu = config.mu;
    add_plane_figures(g.report, cloud,
                      GrowOutcome{g.result.surfaces, g.result.labels, &g.result.stats},
                      compute_bound_planes(cloud, g.result, pc), scene.faces());
    std::cout << name << ": " << eval_line(g.report) << "\n" << bands_line(g.report) << "\n";
    return g;
}

// The scans that attack the method (issue 13): every built-in scene with the laser's optical
// centre on the tilt axis (offset 0: every tilt meets one spot at pan +-90 deg) and 40 mm above
// it; the middle scan alone, and three scans fused with recorded poses 2 mm and 0.1 degree off.
struct Attack {
    std::unique_ptr<scanner::Scene> scene;
    PointCloud single, fused;
};

// The scans of `poses` poses along the scene's scan path, noise drawn from `seed`, the optical
// centre `offset_m` above the tilt axis.
std::vector<scanner::RawScan> simulate_scans(const scanner::Scene& scene, double offset_m,
                                             int poses, std::uint64_t seed = 1) {
    scanner::ScannerSpec spec;
    spec.optical_offset_m = Vec3d(0, 0, offset_m);
    std::vector<scanner::RawScan> raws;
    for (auto& sim : scanner::ScanSimulator(scene, spec)
                         .simulate(scanner::scan_poses(scene.description().scanner, poses), seed))
        raws.push_back(std::move(sim.raw));
    return raws;
}

// The scans fused with recorded poses 2 mm and 0.1 degree off, pose draw `draw`.
PointCloud fuse_with_pose_errors(std::vector<scanner::RawScan> raws, std::uint64_t draw) {
    for (std::size_t k = 0; k < raws.size(); ++k)
        raws[k].pose =
            scanner::perturb_pose(raws[k].pose, 0.002, scanner::deg_to_rad(0.1), mix_seed(draw, k));
    return scanner::fuse_scans(raws);
}

const Attack& attack(const std::string& name, double offset_m) {
    static std::map<std::pair<std::string, double>, Attack> cache;
    const auto key = std::make_pair(name, offset_m);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    Attack a;
    a.scene = std::make_unique<scanner::Scene>(scanner::builtin_scene(name));
    std::vector<scanner::RawScan> raws = simulate_scans(*a.scene, offset_m, 3);
    a.single = scanner::fuse_scans(std::span<const scanner::RawScan>(&raws[1], 1));
    a.fused = fuse_with_pose_errors(std::move(raws), 7);
    return cache.emplace(key, std::move(a)).first->second;
}

// The bounds issue 13 sets for the defaults, on every scene and configuration.
constexpr double kMinRegistered = 0.99;    // planar points, overall and per range band
constexpr double kMaxPatchP95 = 5.0;       // per-point patch normal error, degrees
constexpr double kMaxPlaneP95 = 2.0;       // the same through the bound planes
constexpr double kMaxShareOver45 = 0.005;  // points more than 45 degrees off
constexpr double kMinFacesDetected = 0.9;  // SegComp correct detection, T = 0.8

// Every range band that holds at least 1000 planar points registers at least `bound` of them.
void expect_bands_at_least(const EvalReport& r, double bound) {
    for (const BandReport& b : r.bands) {
        if (b.planar.points < 1000) continue;
        EXPECT_GE(b.planar.fraction(), bound) << b.from_m << "-" << b.to_m << " m";
    }
}

// Test names for suites over noise draws.
std::string noise_draw_name(const ::testing::TestParamInfo<std::uint64_t>& info) {
    return "noise_draw_" + std::to_string(info.param);
}

// Where the defaults do not reach those bounds yet, the bound this scene is held to instead (the
// gaps are in docs/algorithm.md, "What the disk test does not reach yet"): on the pipes' fused
// scans, mixed-pixel veils between a pipe and the wall behind it and the strips where the
// cylinders meet the wall and the floor (the channel's fused scans meet the bound on the tests'
// pose draw since the edge pass; over other draws, see ChannelPoseDraws); and narrow faces (the
// flange edges, a bolt head, the corridor's 10 mm shelf edge, the pipes' valve top in the plane of
// a pipe's crown), whose planes hold 14-26 % points of no face or of the pipe. Single scans meet
// the > 45 degree bound on every scene since mixed-pixel ramps are dropped (0.22-0.29 % on the
// channel), on this noise draw; the channel's end poses on other draws: ChannelEndPoses.
struct Held {
    double fused_over_45 = kMaxShareOver45;  // one scan: always kMaxShareOver45
    double faces = kMinFacesDetected;
};
Held held_to(const std::string& scene) {
    // The pipes' fused > 45 degree share: 0.35-0.56 % on the tests' draw (0.38-0.59 % before
    // thick fused balls were judged within their layers, 0.82 % before the edge pass).
    // Platforms' libm moves these shares too (aarch64 once: +0.3 %).
    if (scene == "ibeam-channel") return {kMaxShareOver45, 0.75};
    if (scene == "pipes") return {0.0065, 0.8};
    if (scene == "corridor") return {kMaxShareOver45, 0.8};
    return {};
}

using AttackCase = std::tuple<std::string, double>;
class AttackScene : public ::testing::TestWithParam<AttackCase> {};

void expect_bounds(const Grown& g, const std::string& scene, bool fused) {
    const EvalReport& r = g.report;
    const Held held = held_to(scene);
    EXPECT_GE(r.planar.fraction(), kMinRegistered);
    expect_bands_at_least(r, kMinRegistered);
    EXPECT_LE(r.normal_deg.p95, kMaxPatchP95);
    const double over_45 = fused ? held.fused_over_45 : kMaxShareOver45;
    EXPECT_LE(r.normal_over_45, over_45);
    ASSERT_TRUE(r.planes.known);
    EXPECT_LE(r.planes.normal_deg.p95, kMaxPlaneP95);
    EXPECT_LE(r.planes.over_45, over_45);
    ASSERT_GT(r.planes.faces_scored, 0u);
    EXPECT_GE(double(r.planes.faces_detected) / double(r.planes.faces_scored), held.faces)
        << r.planes.faces_detected << " of " << r.planes.faces_scored;
    EXPECT_GE(r.facing_sensor.fraction(), 0.99);
    // No accepted surface is a line or a blob.
    for (const Surface& s : g.result.surfaces) {
        ASSERT_GE(s.eigenvalues[1], 0.05 * s.eigenvalues[2]);
        ASSERT_GE(s.eigenvalues[2], 0.05 * s.radius * s.radius);
    }
}

TEST_P(AttackScene, TheDefaultsMeetTheBoundsOnOneScan) {
    const auto& [name, offset] = GetParam();
    const Attack& a = attack(name, offset);
    expect_bounds(grow_and_evaluate(a.single, *a.scene, name, GrowerConfig{}), name, false);
}

TEST_P(AttackScene, TheDefaultsMeetTheBoundsOnThreeFusedScansWithPoseErrors) {
    const auto& [name, offset] = GetParam();
    const Attack& a = attack(name, offset);
    expect_bounds(grow_and_evaluate(a.fused, *a.scene, name, GrowerConfig{}), name, true);
}

INSTANTIATE_TEST_SUITE_P(Scenes, AttackScene,
                         ::testing::Combine(::testing::ValuesIn(scanner::builtin_scene_names()),
                                            ::testing::Values(0.0, 0.040)),
                         [](const auto& param_info) {
                             std::string n = std::get<0>(param_info.param);
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n + (std::get<1>(param_info.param) > 0 ? "_offset_40mm"
                                                                           : "_offset_0");
                         });

// One test per offset: each simulates its three scans once (a whole test ran past ctest's 900 s
// per test under qemu-aarch64).
class ChannelPoseDraws : public ::testing::TestWithParam<double> {};
constexpr double kDrawsMaxShareOver45 = 0.006;
// The channel from four poses (BuiltinSceneIBeam.FourFusedPosesHeldToTheirMeasuredGap): on the
// tests' pose draw 0.5 % and 0.8 % of the points > 45 degrees off (offset 0 and 40 mm), through
// the bound planes 0.5 % and 0.9 % (2.2 % at offset 0 before a strip narrower than its noise
// kept its patches' normal, 2026-12-06); `surfgrow scan --poses 4 --pose-error 2mm
// --pose-error-angle 0.1` draws 0.9-1.3 % and, through the planes, 0.9-1.3 % (was 1.3-2.5 %).
constexpr double kFourPosesOver45 = 0.011;
constexpr double kFourPosesPlanesOver45 = 0.011;

TEST_P(ChannelPoseDraws, FusedScansRegisterEveryRangeBandWhateverThePoseErrorsDraw) {
    // Each face lies a little off in each scan (its range bias there, the pose error), and the
    // leftover pass must take a layer however far the largest of those offsets falls: on pose
    // draw 5 one scan's layer of a top flange's underside lies 9 mm off the others' (3.9 sigmas
    // of the measured offsets), and when 3 sigmas were the limit its 1.5-2 m band kept 97.8 %.
    // Draws 1-5 (the tests above use draw 7); the > 45 degree share must stay within its bound
    // meanwhile: 0.34-0.51 % over draws 1-7 since the edge pass (0.42-0.68 % before; 0.36-0.51 %
    // since thick fused balls are judged within their layers), so 0.6 %
    // here, where the tests' draw meets the 0.5 %.
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const std::string name = "ibeam-channel";
    const double offset = GetParam();
    const scanner::Scene scene(scanner::builtin_scene(name));
    const std::vector<scanner::RawScan> raws = simulate_scans(scene, offset, 3);
    for (const std::uint64_t draw : {1, 2, 3, 4, 5}) {
        const PointCloud fused = fuse_with_pose_errors(raws, draw);
        const GrowResult r = grow_surfaces(fused, GrowerConfig{});
        const EvalReport e = evaluate(fused, r, scene.faces());
        std::cout << "offset " << offset * 1000 << " mm, pose draw " << draw << ": " << eval_line(e)
                  << "\n"
                  << bands_line(e) << "\n";
        SCOPED_TRACE(testing::Message() << "pose draw " << draw);
        expect_bands_at_least(e, kMinRegistered);
        EXPECT_LE(e.normal_over_45, kDrawsMaxShareOver45);
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltinSceneIBeam, ChannelPoseDraws, ::testing::Values(0.0, 0.040),
                         [](const auto& param_info) {
                             return std::string(param_info.param > 0 ? "offset_40mm" : "offset_0");
                         });

// The fused scans above are the tests' noise draw (1). Each draw also draws every scan's range
// bias for every face, and on draws 3 and 5 the scaffold floor's layers, 3-3.3 m away and seen at
// 60-70 degrees, lie 15-20 mm apart along its normal: each ball there was thick, and the floor's
// far band kept 96.3 % (draw 3, 40 mm) and 97.4 % (draw 5, offset 0) of its points, 36-53 degrees
// p95. Balls too thick for the noise are judged within their scans' layers since 2026-12-07
// (docs/algorithm.md, "A thick ball is judged within its scans' layers"): 98.8 % and 99.2 %;
// since such a ball's tolerance spans its layers (2026-12-07; before, the plane lay between the
// layers and the outer layers' farther halves stayed out) 99.6 % and 99.5 %: the bound.
class ChannelNoiseDraws : public ::testing::TestWithParam<std::uint64_t> {};
constexpr double kNoiseDrawsBand = kMinRegistered;

TEST_P(ChannelNoiseDraws, FusedScansRegisterTheFarFloorWhateverTheRangeBiasesDraw) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const std::uint64_t seed = GetParam();
    const scanner::Scene scene(scanner::builtin_scene("ibeam-channel"));
    for (const double offset : {0.0, 0.040}) {
        SCOPED_TRACE(testing::Message() << "noise draw " << seed << ", offset " << offset << " m");
        const PointCloud fused = fuse_with_pose_errors(simulate_scans(scene, offset, 3, seed), 7);
        const EvalReport r =
            grow_and_evaluate(fused, scene, "ibeam-channel fused", GrowerConfig{}).report;
        EXPECT_GE(r.planar.fraction(), kMinRegistered);
        expect_bands_at_least(r, kNoiseDrawsBand);
        EXPECT_LE(r.normal_deg.p95, kMaxPatchP95);
        EXPECT_LE(r.normal_over_45, kDrawsMaxShareOver45);
        ASSERT_TRUE(r.planes.known);
        EXPECT_LE(r.planes.normal_deg.p95, kMaxPlaneP95);
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltinSceneIBeam, ChannelNoiseDraws,
                         ::testing::Values(std::uint64_t{3}, std::uint64_t{5}), noise_draw_name);

TEST(BuiltinSceneIBeam, FourFusedPosesHeldToTheirMeasuredGap) {
    // Four poses along the channel (surfgrow scan --poses 4) put the end scans beside the
    // stiffeners: each 12 mm end face, seen nearly head-on, holds about 1,800 points, and the
    // faces beside it take nearly all of them, as they take the top flanges' 30 mm edges (docs/
    // algorithm.md, "What the disk test does not reach yet"). Three poses hide this: there the
    // ends hold a few hundred points. Held to the level measured on 2026-12-06 so that it cannot
    // grow unseen; issue 13's 0.5 % is not met here.
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const scanner::Scene scene(scanner::builtin_scene("ibeam-channel"));
    for (const double offset : {0.0, 0.040}) {
        const PointCloud fused = fuse_with_pose_errors(simulate_scans(scene, offset, 4), 7);
        const Grown g = grow_and_evaluate(fused, scene, "ibeam-channel, 4 poses", GrowerConfig{});
        const EvalReport& r = g.report;
        EXPECT_GE(r.planar.fraction(), kMinRegistered) << offset;
        expect_bands_at_least(r, kMinRegistered);
        EXPECT_LE(r.normal_deg.p95, kMaxPatchP95) << offset;
        EXPECT_LE(r.planes.normal_deg.p95, kMaxPlaneP95) << offset;
        EXPECT_LE(r.normal_over_45, kFourPosesOver45) << offset;
        EXPECT_LE(r.planes.over_45, kFourPosesPlanesOver45) << offset;
    }
}

// The channel's end poses. The scans above are the middle one of three; from either end the
// stiffener nearest the scanner is seen head-on, 0.75 m away, and its 12 mm end face is a strip
// no wider than the range noise along its normal: patches on it fit across it, and the bound
// planes take their normal (docs/algorithm.md, "What the disk test does not reach yet"). Over
// noise draws 1, 2, 3 and 11 the end scans are 0.37-0.62 % > 45 degrees off, the bound planes
// 0.37-0.62 %, and their worst band registers 98.6-99.98 %; on the tests' draw (1) 0.37-0.43 %.
// Held there, on draws 2 and 3 (the worst).
class ChannelEndPoses : public ::testing::TestWithParam<std::uint64_t> {};
constexpr double kEndPosesOver45 = 0.007;
constexpr double kEndPosesBand = 0.98;

TEST_P(ChannelEndPoses, SingleScansHeldToTheirMeasuredGap) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const std::uint64_t seed = GetParam();
    const scanner::Scene scene(scanner::builtin_scene("ibeam-channel"));
    for (const double offset : {0.0, 0.040}) {
        const std::vector<scanner::RawScan> raws = simulate_scans(scene, offset, 3, seed);
        for (const std::size_t k : {std::size_t{0}, std::size_t{2}}) {
            SCOPED_TRACE(testing::Message()
                         << "noise draw " << seed << ", offset " << offset << " m, scan " << k);
            const PointCloud one = scanner::fuse_scans(std::span(&raws[k], 1));
            const EvalReport r =
                grow_and_evaluate(one, scene, "ibeam-channel end pose", GrowerConfig{}).report;
            EXPECT_GE(r.planar.fraction(), kMinRegistered);
            expect_bands_at_least(r, kEndPosesBand);
            EXPECT_LE(r.normal_deg.p95, kMaxPatchP95);
            EXPECT_LE(r.normal_over_45, kEndPosesOver45);
            ASSERT_TRUE(r.planes.known);
            EXPECT_LE(r.planes.normal_deg.p95, kMaxPlaneP95);
            EXPECT_LE(r.planes.over_45, kEndPosesOver45);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltinSceneIBeam, ChannelEndPoses,
                         ::testing::Values(std::uint64_t{2}, std::uint64_t{3}), noise_draw_name);

// The stairs' side wall far from the scanner (3-4 m, 76 degrees from head-on): its points lie
// 50-100 mm apart, out of the leftover pass's reach of the surfaces grown nearer, yet in their
// plane. Every surface reaches along its face from the points registered since growing
// (detail::extend_surfaces). Before, noise draws 3 and 4 left 1.3-1.6 % of the 3-3.5 m band
// unregistered (98.45-98.83 %), and the 3.5-4 m band (about 500 points, under the 1000 that the
// bands above count) kept 81-86 %; since, 99.36-99.93 % and 89-97 %.
class StairsNoiseDraws : public ::testing::TestWithParam<std::uint64_t> {};
constexpr double kStairsFarBand = 0.88;  // the 3.5-4 m band: measured 89.6-96.9 %

TEST_P(StairsNoiseDraws, OneScanRegistersItsFarSideWall) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const std::uint64_t seed = GetParam();
    const scanner::Scene scene(scanner::builtin_scene("stairs"));
    for (const double offset : {0.0, 0.040}) {
        SCOPED_TRACE(testing::Message() << "noise draw " << seed << ", offset " << offset << " m");
        const std::vector<scanner::RawScan> raws = simulate_scans(scene, offset, 3, seed);
        const PointCloud one = scanner::fuse_scans(std::span(&raws[1], 1));
        const EvalReport r = grow_and_evaluate(one, scene, "stairs", GrowerConfig{}).report;
        EXPECT_GE(r.planar.fraction(), kMinRegistered);
        expect_bands_at_least(r, kMinRegistered);
        for (const BandReport& b : r.bands)
            if (b.planar.points >= 200) {
                EXPECT_GE(b.planar.fraction(), kStairsFarBand) << b.from_m << "-" << b.to_m << " m";
            }
        EXPECT_LE(r.normal_over_45, kMaxShareOver45);
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltinSceneStairs, StairsNoiseDraws,
                         ::testing::Values(std::uint64_t{3}, std::uint64_t{4}), noise_draw_name);

TEST(BuiltinSceneIBeam, TheFlangesInnerEdgesGetSurfacesFacingTheirWay) {
    // The top flanges' inner edges: strips about 25 mm wide facing the channel, between the deck's
    // underside and the flange's, 1-1.9 m from the scanner. No ball that holds enough of one is a
    // disk of it; the strip test grows them from the points the faces around them do not fit.
    for (const double offset : {0.0, 0.040}) {
        const Attack& a = attack("ibeam-channel", offset);
        const GrowResult r = grow_surfaces(a.single, GrowerConfig{});
        const auto& faces = a.scene->faces();
        const auto& primitives = a.scene->description().primitives;
        std::size_t points = 0, registered = 0, facing = 0, far = 0, far_registered = 0;
        const Vec3d origin = a.single.scan_origins.at(0);
        for (std::size_t i = 0; i < a.single.size(); ++i) {
            const std::int32_t f = a.single.labels[i];
            if (f < 0) continue;
            const scanner::Face& face = faces[static_cast<std::size_t>(f)];
            const std::string& name = primitives[static_cast<std::size_t>(face.primitive)].name;
            if (name.find("top-flange") == std::string::npos || std::abs(face.normal.y()) < 0.9)
                continue;
            ++points;
            // Their far ends, two scan lines 25 mm apart: strips grown nearer reach them.
            const bool far_end = (a.single.points[i].cast<double>() - origin).norm() > 1.5;
            far += far_end ? 1 : 0;
            const std::int32_t l = r.labels[i];
            if (l < 0) continue;
            ++registered;
            far_registered += far_end ? 1 : 0;
            const Vec3d& n = r.surfaces[static_cast<std::size_t>(l)].normal;
            facing += std::abs(n.dot(face.normal)) > std::cos(20 * M_PI / 180) ? 1 : 0;
        }
        std::printf(
            "flange edges, offset %.0f mm: %zu points, %.1f %% registered, %.1f %% on "
            "surfaces within 20 deg of their normal; beyond 1.5 m %zu points, %.1f %% "
            "registered\n",
            offset * 1000, points, 100.0 * double(registered) / double(points),
            100.0 * double(facing) / double(points), far,
            100.0 * double(far_registered) / double(std::max<std::size_t>(far, 1)));
        ASSERT_GT(points, 1000u);
        EXPECT_GE(double(registered), 0.85 * double(points));  // 63 % without strips
        EXPECT_GE(double(facing), 0.7 * double(points));       // 48 % without
        ASSERT_GT(far, 30u);
        // 100 % and 77.5 % (offset 0 and 40 mm), 39-40 % before strips reached along their faces
        // (extend_strips). At 40 mm the deck's surfaces hold the edge's points a little nearer
        // (taken across the edge), and no strip reaches past them.
        EXPECT_GE(double(far_registered), 0.7 * double(far));
    }
}

TEST(BuiltinSceneIBeam, StripsAreTheSameForAnyThreadCount) {
    // Strips grow slab by slab, the even slabs at once and then the odd ones: the scan's flange
    // edges span every slab, so the strips of neighbouring slabs meet there.
    const Attack& a = attack("ibeam-channel", 0.0);
    GrowerConfig cfg;
    cfg.threads = 1;
    const GrowResult ref = grow_surfaces(a.single, cfg);
    ASSERT_GT(ref.stats.strip_surfaces, 20u);  // 57
    for (const int threads : {2, 3, 8}) {
        cfg.threads = threads;
        const GrowResult r = grow_surfaces(a.single, cfg);
        EXPECT_EQ(r.stats.strip_surfaces, ref.stats.strip_surfaces) << threads << " threads";
        ASSERT_EQ(r.labels, ref.labels) << threads << " threads";
        ASSERT_EQ(r.surfaces.size(), ref.surfaces.size());
        for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
            ASSERT_EQ(r.surfaces[k].home, ref.surfaces[k].home) << k;
            ASSERT_EQ(r.surfaces[k].normal, ref.surfaces[k].normal) << k;
        }
    }
}

TEST(BuiltinSceneIBeam, TheEdgePassMovesOnlyEdgePointsTheSameForAnyThreadCount) {
    // The fused scans' edge pass (docs/algorithm.md): it moves the points along the edges, a few
    // thousand of 700,000, never the points between coplanar surfaces (without that rule it moved
    // two thirds of the cloud); its moves are decided on one snapshot of the labels.
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const Attack& a = attack("ibeam-channel", 0.0);
    GrowerConfig cfg;
    cfg.threads = 1;
    const GrowResult ref = grow_surfaces(a.fused, cfg);
    std::printf("edge pass: %llu of %llu points moved\n",
                static_cast<unsigned long long>(ref.stats.edge_moves),
                static_cast<unsigned long long>(ref.stats.valid_points));
    EXPECT_GT(ref.stats.edge_moves, 500u);
    EXPECT_LT(double(ref.stats.edge_moves), 0.01 * double(ref.stats.valid_points));
    cfg.threads = 3;
    const GrowResult r = grow_surfaces(a.fused, cfg);
    EXPECT_EQ(r.stats.edge_moves, ref.stats.edge_moves);
    ASSERT_EQ(r.labels, ref.labels);
}

TEST(BuiltinSceneIBeam, ThePapersTestAloneMeetsTheWorkspaceBounds) {
    // Eq. (2) alone at mu = 12 mm, no adaptive radius: the workspace (within 1 m) is dense
    // enough; beyond it the registered share falls (reported by band, not asserted).
    GrowerConfig paper;
    paper.plane_test = PlaneTest::kPaper;
    paper.adaptive_factor = 1.0;
    const Scanned& s = scanned("ibeam-channel");
    const EvalReport r = grow_and_evaluate(s.cloud, *s.scene, "ibeam-channel", paper).report;
    EXPECT_GE(r.planar_workspace.fraction(), 0.99);
    EXPECT_LE(r.normal_workspace_deg.median, 3.0);
    EXPECT_LE(r.normal_deg.median, 3.0);
    EXPECT_GE(r.purity, 0.99);
    ASSERT_GE(r.bands.size(), 3u);
    EXPECT_LT(r.bands[2].planar.fraction(), 0.99);  // 1.0-1.5 m: too sparse for 12 mm
}

TEST(BuiltinSceneIBeam, TheDiskTestCutsThePapersTail) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    // The same scan: the paper's test leaves a tail of normals across edges that the disk test
    // removes, and the defaults register more.
    GrowerConfig paper;
    paper.plane_test = PlaneTest::kPaper;
    paper.adaptive_factor = 2.0;  // the defaults before the disk test
    paper.pool_radius = 2 * paper.mu;
    const Scanned& s = scanned("ibeam-channel");
    const EvalReport p = grow_and_evaluate(s.cloud, *s.scene, "ibeam-channel", paper).report;
    const EvalReport d =
        grow_and_evaluate(s.cloud, *s.scene, "ibeam-channel", GrowerConfig{}).report;
    EXPECT_LT(d.normal_deg.p95, p.normal_deg.p95);
    EXPECT_LT(d.normal_over_45, 0.7 * p.normal_over_45);
    EXPECT_LT(d.planes.over_45, 0.7 * p.planes.over_45);
    // The far bands (2.5 m on): the paper's radius registers a third to three quarters of them.
    EXPECT_LT(p.worst_band_planar(100), 0.9);
    EXPECT_GE(d.worst_band_planar(100), 0.99);
}

class WrongResult : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        const Scanned& s = scanned("room-corner");
        good_ = new GrowResult(grow_surfaces(s.cloud, GrowerConfig{}));
    }
    static void TearDownTestSuite() { delete good_; }
    static EvalReport evaluate_result(const GrowResult& r) {
        const Scanned& s = scanned("room-corner");
        return evaluate(s.cloud, r, s.scene->faces());
    }
    static bool passes(const GrowResult& r, const char* bounds) {
        for (const RequirementCheck& c :
             check_requirements(parse_requirements(bounds), evaluate_result(r)))
            if (!c.met) return false;
        return true;
    }
    static GrowResult* good_;
};
GrowResult* WrongResult::good_ = nullptr;

constexpr const char* kBounds =
    "registered_workspace>=0.99,normal_median<=3,purity>=0.99,facing_sensor>=0.99";

TEST_F(WrongResult, TheGoodResultPasses) {
    EXPECT_TRUE(passes(*good_, kBounds));
}

TEST_F(WrongResult, RotatedNormalsAreCaught) {
    GrowResult bad = *good_;
    const Eigen::AngleAxisd turn(10.0 * 3.14159265358979323846 / 180.0,
                                 Vec3d(1, 1, 1).normalized());
    for (Surface& s : bad.surfaces) s.normal = turn * s.normal;
    const EvalReport r = evaluate_result(bad);
    EXPECT_GT(r.normal_deg.median, 5.0);
    EXPECT_FALSE(passes(bad, kBounds));
}

TEST_F(WrongResult, ShuffledLabelsAreCaught) {
    GrowResult bad = *good_;
    std::mt19937_64 rng(7);
    std::shuffle(bad.labels.begin(), bad.labels.end(), rng);
    const EvalReport r = evaluate_result(bad);
    EXPECT_LT(r.purity, 0.9);
    EXPECT_GT(r.residual_m.mean, 0.05);
    EXPECT_FALSE(passes(bad, kBounds));
}

TEST_F(WrongResult, FlippedNormalsAreCaughtByTheOrientedCheckOnly) {
    GrowResult bad = *good_;
    for (Surface& s : bad.surfaces) s.normal = -s.normal;
    const EvalReport r = evaluate_result(bad);
    EXPECT_LT(r.facing_sensor.fraction(), 0.01);
    EXPECT_DOUBLE_EQ(r.normal_deg.median, evaluate_result(*good_).normal_deg.median);
    EXPECT_FALSE(passes(bad, kBounds));
}

}  // namespace
}  // namespace surfgrow::eval
