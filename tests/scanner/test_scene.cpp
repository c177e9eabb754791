// The ray caster against analytic intersections, occlusion, faces, the BVH, built-in scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "surfgrow/core/error.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace {

using namespace surfgrow::scanner;
using surfgrow::Error;
using surfgrow::ErrorCode;
using surfgrow::Mat3d;
using surfgrow::Vec3d;

Scene one(Shape shape) {
    return Scene(SceneDescription{"t", {{"p", std::move(shape)}}, {}});
}

Hit must_hit(const Scene& s, const Vec3d& o, const Vec3d& d, double t_max = 100.0) {
    const auto h = s.intersect(Ray{o, d.normalized()}, t_max);
    EXPECT_TRUE(h.has_value());
    return h.value_or(Hit{});
}

TEST(RayCast, Rectangle) {
    const Scene s = one(Rectangle{Vec3d(2, 0, 0), Vec3d::UnitY(), Vec3d::UnitZ(), 0.5, 0.25});
    Hit h = must_hit(s, Vec3d::Zero(), Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(h.t, 2.0);
    EXPECT_EQ(h.face_id, 0);
    EXPECT_EQ(h.primitive, 0);
    EXPECT_NEAR((h.normal - Vec3d(-1, 0, 0)).norm(), 0.0, 1e-12);  // faces the ray origin
    // From behind: seen too, normal facing that side.
    h = must_hit(s, Vec3d(4, 0, 0), -Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(h.t, 2.0);
    EXPECT_NEAR((h.normal - Vec3d(1, 0, 0)).norm(), 0.0, 1e-12);
    // Oblique ray to a corner inside the bounds: t = |(2, 0.4, 0.2)|.
    h = must_hit(s, Vec3d::Zero(), Vec3d(2, 0.4, 0.2));
    EXPECT_NEAR(h.t, std::sqrt(4 + 0.16 + 0.04), 1e-12);
    EXPECT_FALSE(s.intersect(Ray{Vec3d::Zero(), Vec3d(2, 0.6, 0).normalized()}, 100));  // beside
    EXPECT_FALSE(s.intersect(Ray{Vec3d::Zero(), Vec3d(2, 0, 0.3).normalized()}, 100));  // above
    EXPECT_FALSE(s.intersect(Ray{Vec3d::Zero(), Vec3d::UnitY()}, 100));                 // parallel
    EXPECT_FALSE(s.intersect(Ray{Vec3d::Zero(), -Vec3d::UnitX()}, 100));                // behind
    EXPECT_FALSE(s.intersect(Ray{Vec3d::Zero(), Vec3d::UnitX()}, 1.9));                 // t_max
}

TEST(RayCast, BoxFacesAndRotation) {
    const Scene s = one(Box{Vec3d::Zero(), Mat3d::Identity(), Vec3d(0.5, 1.0, 1.5)});
    Hit h = must_hit(s, Vec3d(-5, 0.1, 0.2), Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(h.t, 4.5);
    EXPECT_EQ(h.face_id, 1);  // -x
    EXPECT_NEAR((h.normal - Vec3d(-1, 0, 0)).norm(), 0.0, 1e-12);
    h = must_hit(s, Vec3d(0, 0, 10), -Vec3d::UnitZ());
    EXPECT_DOUBLE_EQ(h.t, 8.5);
    EXPECT_EQ(h.face_id, 4);  // +z
    h = must_hit(s, Vec3d(0, -3, 0), Vec3d::UnitY());
    EXPECT_EQ(h.face_id, 3);  // -y
    // From inside: the far face, normal facing back at the origin.
    h = must_hit(s, Vec3d::Zero(), Vec3d::UnitY());
    EXPECT_DOUBLE_EQ(h.t, 1.0);
    EXPECT_EQ(h.face_id, 2);
    EXPECT_NEAR((h.normal - Vec3d(0, -1, 0)).norm(), 0.0, 1e-12);

    Box rotated;
    rotated.rotation = rotation_from_rpy(Vec3d(0, 0, M_PI / 6));
    rotated.half_size_m = Vec3d::Constant(0.5);
    const Scene r = one(rotated);
    const double to_face = 0.5 / std::cos(M_PI / 6);
    h = must_hit(r, Vec3d(-5, 0, 0), Vec3d::UnitX());
    EXPECT_NEAR(h.t, 5 - to_face, 1e-12);
    EXPECT_EQ(h.face_id, 1);
    EXPECT_NEAR((h.normal + rotated.rotation.col(0)).norm(), 0.0, 1e-12);
}

TEST(RayCast, CylinderSideAndCaps) {
    const Scene s = one(Cylinder{Vec3d(0, 0, 0), Vec3d(0, 0, 2), 0.5, true});
    Hit h = must_hit(s, Vec3d(-3, 0, 1), Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(h.t, 2.5);
    EXPECT_EQ(h.face_id, 0);
    EXPECT_NEAR((h.normal - Vec3d(-1, 0, 0)).norm(), 0.0, 1e-12);
    // Off-centre: chord at y = 0.3 enters at x = -0.4; radial normal (-0.8, 0.6, 0).
    h = must_hit(s, Vec3d(-3, 0.3, 1), Vec3d::UnitX());
    EXPECT_NEAR(h.t, 2.6, 1e-12);
    EXPECT_NEAR((h.normal - Vec3d(-0.8, 0.6, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((s.normal_at(0, Vec3d(-0.4, 0.3, 1.7)) - Vec3d(-0.8, 0.6, 0)).norm(), 0.0, 1e-12);
    h = must_hit(s, Vec3d(0.1, 0.2, 5), -Vec3d::UnitZ());
    EXPECT_DOUBLE_EQ(h.t, 3.0);
    EXPECT_EQ(h.face_id, 2);  // top cap
    EXPECT_NEAR((h.normal - Vec3d::UnitZ()).norm(), 0.0, 1e-12);
    h = must_hit(s, Vec3d(0.3, 0, -1), Vec3d::UnitZ());
    EXPECT_DOUBLE_EQ(h.t, 1.0);
    EXPECT_EQ(h.face_id, 1);                                                 // base cap
    EXPECT_FALSE(s.intersect(Ray{Vec3d(-3, 0, 2.1), Vec3d::UnitX()}, 100));  // above the top
    EXPECT_FALSE(s.intersect(Ray{Vec3d(-3, 0.6, 1), Vec3d::UnitX()}, 100));  // beside

    const Scene tube = one(Cylinder{Vec3d(0, 0, 0), Vec3d(0, 0, 2), 0.5, false});
    EXPECT_EQ(tube.faces().size(), 1u);
    EXPECT_FALSE(tube.intersect(Ray{Vec3d(0.1, 0, 5), -Vec3d::UnitZ()}, 100));  // through the bore
    h = must_hit(tube, Vec3d(0, 0, 1), Vec3d::UnitX());                         // from inside
    EXPECT_DOUBLE_EQ(h.t, 0.5);
    EXPECT_NEAR((h.normal - Vec3d(-1, 0, 0)).norm(), 0.0, 1e-12);
}

TEST(RayCast, NearestHitWinsAndOccludes) {
    SceneDescription d;
    d.primitives.push_back(
        {"far", Rectangle{Vec3d(3, 0, 0), Vec3d::UnitY(), Vec3d::UnitZ(), 2, 2}});
    d.primitives.push_back({"near", Box::from_min_max(Vec3d(1, -0.2, -0.2), Vec3d(1.1, 0.2, 0.2))});
    const Scene s(d);
    Hit h = must_hit(s, Vec3d::Zero(), Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(h.t, 1.0);
    EXPECT_EQ(h.primitive, 1);
    EXPECT_EQ(h.face_id, 1 + 1);                     // the box's -x face; the rectangle is face 0
    h = must_hit(s, Vec3d::Zero(), Vec3d(3, 1, 0));  // y = 0.33 at the box: beside it
    EXPECT_EQ(h.primitive, 0);
    EXPECT_NEAR(h.t, std::sqrt(10.0), 1e-12);
}

TEST(RayCast, BvhAgreesWithBruteForceOnTheIBeamChannel) {
    const SceneDescription d = ibeam_channel_scene();
    const Scene scene(d);
    std::vector<Scene> singles;
    std::vector<int> first_face;
    for (std::size_t i = 0; i < d.primitives.size(); ++i) {
        singles.push_back(one(d.primitives[i].shape));
        int f = 0;
        while (scene.faces()[static_cast<std::size_t>(f)].primitive != static_cast<int>(i)) ++f;
        first_face.push_back(f);
    }
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int hits = 0;
    for (int k = 0; k < 20000; ++k) {
        const Vec3d o(1.5 * u(rng), 0.5 * u(rng), 1.45 + 0.5 * u(rng));
        const Ray ray{o, Vec3d(u(rng), u(rng), u(rng)).normalized()};
        Hit best;
        best.t = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < singles.size(); ++i) {
            if (auto h = singles[i].intersect(ray, 4.0); h && h->t < best.t) {
                best = *h;
                best.face_id += first_face[i];
            }
        }
        const auto h = scene.intersect(ray, 4.0);
        ASSERT_EQ(h.has_value(), std::isfinite(best.t)) << "ray " << k;
        if (!h) continue;
        ++hits;
        EXPECT_NEAR(h->t, best.t, 1e-12) << "ray " << k;
        if (std::abs(h->t - best.t) < 1e-9 && h->face_id != best.face_id) {
            // Ties at touching faces (flange against web) may go either way; both are at t.
            continue;
        }
        EXPECT_EQ(h->face_id, best.face_id) << "ray " << k;
    }
    EXPECT_GT(hits, 15000);
}

TEST(Scene, FacesOfABoxFaceOutward) {
    const Scene s =
        one(Box{Vec3d(1, 2, 3), rotation_from_rpy(Vec3d(0.2, 0.3, 0.4)), Vec3d(0.1, 0.2, 0.3)});
    ASSERT_EQ(s.faces().size(), 6u);
    for (const Face& f : s.faces()) {
        EXPECT_TRUE(f.planar());
        EXPECT_GT((f.center - Vec3d(1, 2, 3)).dot(f.normal), 0.0);
        EXPECT_NEAR((f.u_axis.cross(f.v_axis) - f.normal).norm(), 0.0, 1e-12);
        EXPECT_NEAR(f.plane().signed_distance(f.center), 0.0, 1e-12);
    }
    EXPECT_NEAR(s.faces()[0].half_u_m * s.faces()[0].half_v_m, 0.2 * 0.3, 1e-12);
    EXPECT_EQ(s.planar_faces().size(), 6u);
    EXPECT_THROW((void)s.normal_at(6, Vec3d::Zero()), Error);
}

void expect_invalid(Shape shape, const char* what) {
    try {
        (void)Scene(SceneDescription{"t", {{"thing", std::move(shape)}}, {}});
        FAIL() << what << " accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << what;
        EXPECT_NE(std::string(e.what()).find("'thing'"), std::string::npos) << e.what();
    }
}

TEST(Scene, BadPrimitivesAreInvalidParameters) {
    expect_invalid(Rectangle{Vec3d::Zero(), Vec3d::UnitX(), Vec3d(1, 1, 0), 1, 1}, "skew axes");
    expect_invalid(Rectangle{Vec3d::Zero(), Vec3d::UnitX(), Vec3d::UnitY(), -1, 1}, "negative");
    expect_invalid(Rectangle{Vec3d::Zero(), Vec3d::Zero(), Vec3d::UnitY(), 1, 1}, "zero axis");
    expect_invalid(Box{Vec3d::Zero(), 2 * Mat3d::Identity(), Vec3d::Ones()}, "scaled rotation");
    expect_invalid(Box{Vec3d::Zero(), -Mat3d::Identity(), Vec3d::Ones()}, "reflection");
    expect_invalid(Box{Vec3d::Zero(), Mat3d::Identity(), Vec3d(1, 0, 1)}, "flat box");
    expect_invalid(Box{Vec3d(std::nan(""), 0, 0), Mat3d::Identity(), Vec3d::Ones()}, "NaN");
    expect_invalid(Cylinder{Vec3d::Zero(), Vec3d::Zero(), 1, true}, "zero length");
    expect_invalid(Cylinder{Vec3d::Zero(), Vec3d::UnitZ(), 0, true}, "zero radius");
    expect_invalid(Cylinder{Vec3d::Zero(), Vec3d(1e9, 0, 0), 1, true}, "huge");
}

TEST(BuiltinScenes, AllBuildWithTheirFaceCounts) {
    EXPECT_EQ(builtin_scene_names().size(), 5u);
    for (const std::string& name : builtin_scene_names()) {
        const Scene s(builtin_scene(name));
        EXPECT_EQ(s.description().name, name);
        EXPECT_GT(s.faces().size(), 0u);
    }
    EXPECT_EQ(Scene(ibeam_channel_scene()).primitive_count(), 42u);
    EXPECT_EQ(Scene(ibeam_channel_scene()).faces().size(),
              1u + 6u + 6u * 6u + 8u * 6u + 2u * 6u + 24u * 3u);
    EXPECT_EQ(Scene(room_corner_scene()).primitive_count(), 3u);
    EXPECT_EQ(Scene(pipes_scene()).primitive_count(), 14u);
    EXPECT_EQ(Scene(corridor_scene()).primitive_count(), 9u);
    EXPECT_EQ(Scene(stairs_scene()).primitive_count(), 13u);
    try {
        (void)builtin_scene("bridge");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
        EXPECT_NE(std::string(e.what()).find("ibeam-channel"), std::string::npos);
    }
}

TEST(BuiltinScenes, TheCorridorHasWallsAtBothPolesOfTheTiltAxisAndAFarEndWall) {
    const SceneDescription d = corridor_scene();
    const Scene s(d);
    const Vec3d o = d.scanner.home.translation();
    // The tilt axis is the sensor's y: along it, each side wall 1 m away, hit head-on.
    const Vec3d axis = d.scanner.home.linear() * Vec3d::UnitY();
    for (const double side : {1.0, -1.0}) {
        const Hit h = must_hit(s, o, side * axis);
        EXPECT_NEAR(h.t, 1.0, 1e-9);
        EXPECT_NEAR(std::abs(h.normal.dot(axis)), 1.0, 1e-9);
    }
    // Straight ahead: the end wall at 3.5 m, inside the URG's 4 m.
    const Vec3d ahead = d.scanner.home.linear() * Vec3d::UnitX();
    EXPECT_NEAR(must_hit(s, o, ahead).t, 3.5, 1e-9);
}

TEST(BuiltinScenes, TheStairsHaveTreadsAndRisersAndASideWallAtThePole) {
    const SceneDescription d = stairs_scene();
    const Scene s(d);
    const Vec3d o = d.scanner.home.translation();
    const Vec3d axis = d.scanner.home.linear() * Vec3d::UnitY();
    EXPECT_NEAR(must_hit(s, o, axis).t, 0.9, 1e-9);  // the side wall, at the pole
    // Looking down the flight: a riser (normal -x) or a tread (normal +z), never anything else.
    int risers = 0, treads = 0;
    for (double x = 1.05; x < 2.6; x += 0.07) {
        const Hit h = must_hit(s, Vec3d(x, 0, 2.5), Vec3d(0.3, 0, -1).normalized());
        risers += h.normal.isApprox(-Vec3d::UnitX(), 1e-9) ? 1 : 0;
        treads += h.normal.isApprox(Vec3d::UnitZ(), 1e-9) ? 1 : 0;
        EXPECT_TRUE(h.normal.isApprox(-Vec3d::UnitX(), 1e-9) ||
                    h.normal.isApprox(Vec3d::UnitZ(), 1e-9));
    }
    EXPECT_GT(risers, 0);
    EXPECT_GT(treads, 0);
}

TEST(BuiltinScenes, IBeamChannelHasRealisticDimensionsAndAScannerInTheChannel) {
    const IBeamChannelParams p;
    EXPECT_GE(p.depth_m, 0.9);
    EXPECT_LE(p.depth_m, 1.2);
    EXPECT_GE(p.flange_width_m, 0.30);
    EXPECT_LE(p.flange_width_m, 0.45);
    EXPECT_GE(p.flange_thickness_m, 0.020);
    EXPECT_LE(p.flange_thickness_m, 0.040);
    EXPECT_GE(p.web_thickness_m, 0.010);
    EXPECT_LE(p.web_thickness_m, 0.016);
    const SceneDescription d = ibeam_channel_scene();
    const Scene s(d);
    const Vec3d o = d.scanner.home.translation();
    // Up to the deck, across to both webs' stiffened inner faces: all within the paper's ~1 m.
    const Hit up = must_hit(s, o, Vec3d::UnitZ());
    EXPECT_NEAR(up.t, p.girder_bottom_z_m + p.depth_m - p.scanner_height_m, 1e-9);
    for (const double side : {1.0, -1.0}) {
        const Hit h = must_hit(s, o + Vec3d(0.4, 0, 0), Vec3d(0, side, 0));
        EXPECT_NEAR(h.t, 0.5 * (p.girder_spacing_m - p.web_thickness_m), 1e-9);
        EXPECT_GE(h.t, 0.5);
        EXPECT_LE(h.t, 1.0);
    }
    // The scanner looks up: its forward axis is world +z, its tilt axis world y.
    EXPECT_NEAR((d.scanner.home.linear() * Vec3d::UnitX() - Vec3d::UnitZ()).norm(), 0, 1e-12);
    EXPECT_NEAR((d.scanner.home.linear() * Vec3d::UnitY() - Vec3d::UnitY()).norm(), 0, 1e-12);
}

TEST(ScanPoses, AreSpacedAlongThePathAroundHome) {
    ScanPath path;
    path.home = pose_from_xyz_rpy(Vec3d(1, 2, 3), Vec3d(0, 0, 0.5));
    path.step_m = Vec3d(0.5, 0, 0);
    const auto poses = scan_poses(path, 3);
    ASSERT_EQ(poses.size(), 3u);
    EXPECT_NEAR((poses[0].translation() - Vec3d(0.5, 2, 3)).norm(), 0, 1e-12);
    EXPECT_NEAR((poses[1].translation() - Vec3d(1, 2, 3)).norm(), 0, 1e-12);
    EXPECT_NEAR((poses[2].translation() - Vec3d(1.5, 2, 3)).norm(), 0, 1e-12);
    EXPECT_TRUE(poses[2].linear().isApprox(path.home.linear()));
    EXPECT_EQ(scan_poses(path, 1).front().translation(), path.home.translation());
    EXPECT_THROW((void)scan_poses(path, 0), Error);
}

}  // namespace
