// The URG-04LX presets, the tilting scanner's frames and the pose conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surfgrow/core/error.hpp"
#include "surfgrow/scanner/laser_spec.hpp"
#include "surfgrow/scanner/pose.hpp"
#include "surfgrow/scanner/tilting_scanner.hpp"

namespace {

using namespace surfgrow::scanner;
using surfgrow::Error;
using surfgrow::ErrorCode;
using surfgrow::Mat3d;
using surfgrow::Vec3d;

int detect_count(const LaserSpec& s) {
    int n = 0;
    for (int i = 0; i < s.steps(); ++i) n += s.can_detect(i) ? 1 : 0;
    return n;
}

TEST(LaserSpec, PaperLayoutIs768StepsOf036DegWithA240DegFan) {
    const LaserSpec s = urg04lx_paper();
    EXPECT_EQ(s.steps(), 768);
    EXPECT_DOUBLE_EQ(s.step_deg, 0.36);
    EXPECT_DOUBLE_EQ(s.pan_deg(384), 0.0);
    EXPECT_DOUBLE_EQ(s.pan_deg(0), -138.24);
    EXPECT_EQ(detect_count(s), 667);
    EXPECT_NEAR(s.pan_deg(51), -119.88, 1e-9);
    EXPECT_NEAR(s.pan_deg(717), 119.88, 1e-9);
    EXPECT_EQ(s.min_range_mm, 20);
    EXPECT_EQ(s.max_range_mm, 4000);
    EXPECT_NO_THROW(s.validate());
}

TEST(LaserSpec, ScipLayoutsMatchTheDevice) {
    const LaserSpec a = urg04lx_scip_682();
    EXPECT_EQ(a.steps(), 682);
    EXPECT_EQ(detect_count(a), 682);
    EXPECT_DOUBLE_EQ(a.pan_deg(0), (44 - 384) * 360.0 / 1024.0);
    EXPECT_DOUBLE_EQ(a.pan_deg(681), (725 - 384) * 360.0 / 1024.0);
    const LaserSpec b = urg04lx_scip_769();
    EXPECT_EQ(b.steps(), 769);
    EXPECT_DOUBLE_EQ(b.pan_deg(0), -135.0);
    EXPECT_DOUBLE_EQ(b.pan_deg(768), 135.0);
    EXPECT_DOUBLE_EQ(b.pan_deg(384), 0.0);
    EXPECT_FALSE(b.can_detect(43));
    EXPECT_TRUE(b.can_detect(44));
    EXPECT_TRUE(b.can_detect(725));
    EXPECT_FALSE(b.can_detect(726));
    EXPECT_EQ(detect_count(b), 682);
    EXPECT_EQ(laser_preset("urg04lx-769"), b);
    EXPECT_EQ(laser_preset("urg04lx-682"), a);
    EXPECT_EQ(laser_preset("urg04lx-paper"), urg04lx_paper());
    EXPECT_EQ(laser_preset_names().size(), 3u);
}

TEST(LaserSpec, UnknownPresetAndBadValuesAreInvalidParameters) {
    try {
        (void)laser_preset("urg-99");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
    }
    LaserSpec s;
    s.min_range_mm = 5000;
    EXPECT_THROW(s.validate(), Error);
    s = LaserSpec{};
    s.step_deg = 0.0;
    EXPECT_THROW(s.validate(), Error);
    s = LaserSpec{};
    s.last_detect_step = 900;
    EXPECT_THROW(s.validate(), Error);
    // Found by fuzz/raw_scan: a front step far from the sweep overflowed int (UBSan).
    for (int front : {std::numeric_limits<int>::min(), std::numeric_limits<int>::max()}) {
        s = LaserSpec{};
        s.front_step = front;
        EXPECT_THROW(s.validate(), Error) << front;
    }
    TiltSpec t;
    t.positions = 0;
    EXPECT_THROW(t.validate(), Error);
    ScannerSpec sc;
    sc.readings_per_ray = 0;
    EXPECT_THROW(sc.validate(), Error);
    sc = ScannerSpec{};
    sc.optical_offset_m = Vec3d(std::nan(""), 0, 0);
    EXPECT_THROW(sc.validate(), Error);
}

TEST(TiltSpec, PaperValuesGive360PositionsFromMinus60In13Deg) {
    const TiltSpec t;
    EXPECT_EQ(t.positions, 360);
    EXPECT_DOUBLE_EQ(t.tilt_deg(0), -60.0);
    EXPECT_NEAR(t.tilt_deg(180), 0.0, 1e-12);
    EXPECT_NEAR(t.last_deg(), 60.0 - 1.0 / 3.0, 1e-12);
    // 360 x 768 rays: the paper's maximum of 276480 points per scan.
    EXPECT_EQ(ScannerSpec{}.rays(), 276480u);
}

TEST(TiltingScanner, BeamDirectionsFollowTheFrameConvention) {
    ScannerSpec spec;
    spec.optical_offset_m = Vec3d::Zero();
    const TiltingScanner sc(spec);
    const int level = 180, front = 384;  // tilt 0, pan 0
    EXPECT_NEAR((sc.ray(level, front).direction - Vec3d::UnitX()).norm(), 0.0, 1e-12);
    // Pan +90 deg (250 steps of 0.36) turns toward +y.
    EXPECT_NEAR((sc.ray(level, front + 250).direction - Vec3d::UnitY()).norm(), 0.0, 1e-12);
    // Tilt +30 deg (index 270) raises the beam toward +z.
    const double t = 30.0 * M_PI / 180.0;
    EXPECT_NEAR((sc.ray(270, front).direction - Vec3d(std::cos(t), 0, std::sin(t))).norm(), 0.0,
                1e-12);
    // A pan-90 beam lies on the tilt axis: tilting does not move it.
    EXPECT_NEAR((sc.ray(0, front + 250).direction - Vec3d::UnitY()).norm(), 0.0, 1e-12);
}

TEST(TiltingScanner, KnownWallGivesPointsOnIt) {
    ScannerSpec spec;
    spec.optical_offset_m = Vec3d::Zero();
    const TiltingScanner sc(spec);
    // Wall x = 1 m: the range along (tilt t, pan p) is 1 / (cos p cos t).
    for (int i = 0; i < sc.tilt_count(); i += 17) {
        for (int j = 300; j < 470; j += 13) {
            const double r = 1.0 / (std::cos(sc.pan_rad(j)) * std::cos(sc.tilt_rad(i)));
            const Vec3d p = sc.to_sensor(i, j, r);
            EXPECT_NEAR(p.x(), 1.0, 1e-12);
            EXPECT_NEAR(p.y(), std::tan(sc.pan_rad(j)) / std::cos(sc.tilt_rad(i)), 1e-12);
            EXPECT_NEAR(p.z(), std::tan(sc.tilt_rad(i)), 1e-12);
        }
    }
    // The paper's Fig. 2c: at 1 m adjacent points are about 6 mm apart in both directions.
    const double pan_gap = (sc.to_sensor(180, 384, 1.0) - sc.to_sensor(180, 385, 1.0)).norm();
    const double tilt_gap = (sc.to_sensor(180, 384, 1.0) - sc.to_sensor(181, 384, 1.0)).norm();
    EXPECT_NEAR(pan_gap, 2 * std::sin(0.18 * M_PI / 180.0), 1e-12);
    EXPECT_NEAR(tilt_gap, 2 * std::sin(M_PI / 1080.0), 1e-12);
}

TEST(TiltingScanner, OpticalOffsetSwingsWithTheTilt) {
    ScannerSpec spec;
    spec.optical_offset_m = Vec3d(0.05, 0.0, 0.10);
    const TiltingScanner sc(spec);
    EXPECT_NEAR((sc.optical_centre(180) - Vec3d(0.05, 0, 0.10)).norm(), 0.0, 1e-12);
    const double t = 30.0 * M_PI / 180.0, c = std::cos(t), s = std::sin(t);
    const Vec3d expected(0.05 * c - 0.10 * s, 0.0, 0.05 * s + 0.10 * c);
    EXPECT_NEAR((sc.optical_centre(270) - expected).norm(), 0.0, 1e-12);
    // A point is the optical centre plus the range along the beam.
    const Ray ray = sc.ray(270, 400);
    EXPECT_NEAR((sc.to_sensor(270, 400, 1.5) - (ray.origin + 1.5 * ray.direction)).norm(), 0.0,
                1e-12);
    // Zero range is the optical centre, not the tilt axis.
    EXPECT_NEAR((sc.to_sensor(270, 400, 0.0) - expected).norm(), 0.0, 1e-12);
}

TEST(TiltingScanner, ToWorldAppliesThePose) {
    const TiltingScanner sc;
    const Pose pose = pose_from_xyz_rpy(Vec3d(1, 2, 3), Vec3d(0, 0, M_PI / 2));
    const Vec3d ps = sc.to_sensor(100, 200, 2.0);
    const Vec3d pw = sc.to_world(pose, 100, 200, 2.0);
    EXPECT_NEAR((pw - Vec3d(1 - ps.y(), 2 + ps.x(), 3 + ps.z())).norm(), 0.0, 1e-12);
}

TEST(Pose, RpyConventionIsFixedAxesRollPitchYaw) {
    auto rot = [](double r, double p, double y) {
        return rotation_from_rpy(Vec3d(r, p, y) * M_PI / 180.0);
    };
    EXPECT_NEAR((rot(0, 0, 90) * Vec3d::UnitX() - Vec3d::UnitY()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((rot(0, -90, 0) * Vec3d::UnitX() - Vec3d::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((rot(90, 0, 0) * Vec3d::UnitY() - Vec3d::UnitZ()).norm(), 0.0, 1e-12);
    // Roll first, then pitch, then yaw, all about the fixed axes.
    const auto r = rot(90, 0, 90);
    EXPECT_NEAR((r * Vec3d::UnitY() - Vec3d::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r * Vec3d::UnitX() - Vec3d::UnitY()).norm(), 0.0, 1e-12);
}

TEST(Pose, RpyRoundTrips) {
    for (const Vec3d& deg :
         {Vec3d(10, 20, 30), Vec3d(-170, 45, 100), Vec3d(0, -89, -179), Vec3d(5, 0, 0)}) {
        const Vec3d rad = deg * M_PI / 180.0;
        EXPECT_NEAR((rpy_from_rotation(rotation_from_rpy(rad)) - rad).norm(), 0.0, 1e-9);
    }
    // Gimbal lock: the rotation is still reproduced.
    const Mat3d lock = rotation_from_rpy(Vec3d(0.3, M_PI / 2, 0.5));
    EXPECT_NEAR((rotation_from_rpy(rpy_from_rotation(lock)) - lock).norm(), 0.0, 1e-9);
}

void expect_not_rigid(const Eigen::Matrix4d& m, const char* why) {
    try {
        (void)rigid_from_matrix(m);
        FAIL() << why << " accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << why;
    }
}

TEST(Pose, RigidTransformsAreValidatedAndOrthonormalised) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = rotation_from_rpy(Vec3d(0.1, 0.2, 0.3));
    m.topRightCorner<3, 1>() = Vec3d(1, 2, 3);
    Eigen::Matrix4d typed = m;
    typed.topLeftCorner<3, 3>() = (m.topLeftCorner<3, 3>() * 1e5).array().round() / 1e5;
    const Pose p = rigid_from_matrix(typed);  // 5-digit entries pass
    const Mat3d r = p.linear();
    EXPECT_NEAR((r.transpose() * r - Mat3d::Identity()).norm(), 0.0, 1e-14);
    EXPECT_NEAR(p.translation().x(), 1.0, 0.0);

    Eigen::Matrix4d scaled = m;
    scaled.topLeftCorner<3, 3>() *= 1.01;
    expect_not_rigid(scaled, "scale");
    Eigen::Matrix4d sheared = m;
    sheared(0, 1) += 0.05;
    expect_not_rigid(sheared, "shear");
    Eigen::Matrix4d mirrored = m;
    mirrored.col(0) = -mirrored.col(0);
    expect_not_rigid(mirrored, "reflection");
    Eigen::Matrix4d bottom = m;
    bottom(3, 0) = 0.5;
    expect_not_rigid(bottom, "bottom row");
    Eigen::Matrix4d nan = m;
    nan(1, 3) = std::nan("");
    expect_not_rigid(nan, "NaN");
}

}  // namespace
