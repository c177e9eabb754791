// Taking a scan with the real drivers against the emulated rig: the read-back angles place the
// rays (a lagging servo bends nothing), a device failing mid-scan leaves a partial scan that is
// kept and refused for fusing, and the emulation is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/scanner/acquisition.hpp"
#include "surfgrow/scanner/emulated_rig.hpp"
#include "surfgrow/scanner/fuse.hpp"

namespace surfgrow::scanner {
namespace {

// One wall, the plane x = 1.5 m, 6 m wide and 8 m high: every ray at tilt -40..40 deg meets it.
Scene wall() {
    SceneDescription d;
    Rectangle r;
    r.center = Vec3d(1.5, 0, 0);
    r.u_axis = Vec3d::UnitY();
    r.v_axis = Vec3d::UnitZ();
    r.half_u_m = 3.0;
    r.half_v_m = 4.0;
    d.primitives.push_back({"wall", r});
    return Scene(std::move(d));
}

ScannerSpec plan(int positions) {
    ScannerSpec s;
    s.laser = urg04lx_scip_682();
    s.tilt.first_deg = -40.0;
    s.tilt.step_deg = 80.0 / (positions - 1);
    s.tilt.positions = positions;
    s.readings_per_ray = 3;
    return s;
}

struct Rig {
    EmulatedRig rig;
    UrgDriver urg;
    dxl::ServoDriver servo;
    Rig(const Scene& scene, const ScannerSpec& spec, NoiseModel noise, UrgFaults uf = {},
        dxl::ServoFaults sf = {})
        : rig(scene, spec, {noise, Pose::Identity(), 7, uf, sf}),
          urg([this](std::string_view c) { return rig.urg_reply(c); }),
          servo([this](std::string_view p) { return rig.servo_reply(p); }) {}
};

// Largest |x - 1.5| of the scan's points, metres.
double off_wall(const RawScan& scan) {
    const PointCloud c = fuse_scans(std::span(&scan, 1));
    double worst = 0;
    for (const Vec3f& p : c.points) worst = std::max(worst, std::abs(double(p.x()) - 1.5));
    return worst;
}

TEST(Acquisition, TheReadBackAnglePlacesTheRaysNotThePlannedOne) {
    const Scene scene = wall();
    dxl::ServoFaults lag;
    lag.lag_ticks = 6;  // settles 0.53 deg past every goal: a loaded gear
    Rig r(scene, plan(21), NoiseModel::ideal(), {}, lag);
    const RawScan scan = acquire_scan(r.urg, r.servo, plan(21), Pose::Identity());
    ASSERT_EQ(scan.spec.tilt.positions, 21);
    EXPECT_FALSE(scan.partial());
    ASSERT_EQ(scan.tilt_read_deg.size(), 21u);
    for (int i = 0; i < 21; ++i)
        EXPECT_NEAR(scan.tilt_read_deg[i] - scan.spec.tilt.tilt_deg(i), 6 * 360.0 / 4096, 0.05);
    EXPECT_EQ(scan.sensor_time_ms.size(), 21u);
    EXPECT_TRUE(std::is_sorted(scan.sensor_time_ms.begin(), scan.sensor_time_ms.end()));
    EXPECT_NE(scan.note.find("URG-04LX"), std::string::npos);
    // Placed at the angles read back, the wall is flat to the readings' millimetre; placed at
    // the planned angles it bends by the lag times the height (0.53 deg x 1.3 m = 12 mm).
    EXPECT_LT(off_wall(scan), 0.002);
    RawScan planned = scan;
    planned.tilt_read_deg.clear();
    EXPECT_GT(off_wall(planned), 0.008);
    // The rig's ground truth: the wall (face 0) where the beam met it (pan within +-63 deg,
    // about half the fan), nothing elsewhere.
    for (const double deg : scan.tilt_read_deg) {
        const std::vector<std::int32_t> t = r.rig.truth_at(deg);
        ASSERT_EQ(t.size(), static_cast<std::size_t>(scan.spec.laser.steps()));
        const auto on_wall = std::count(t.begin(), t.end(), 0);
        EXPECT_EQ(on_wall + std::count(t.begin(), t.end(), -1), std::ptrdiff_t(t.size()));
        EXPECT_GT(on_wall, std::ptrdiff_t(t.size() * 4 / 10));
    }
}

TEST(Acquisition, DeterministicForTheSameCommandsAndSeed) {
    const Scene scene = wall();
    Rig a(scene, plan(9), NoiseModel{}), b(scene, plan(9), NoiseModel{});
    const RawScan sa = acquire_scan(a.urg, a.servo, plan(9), Pose::Identity());
    const RawScan sb = acquire_scan(b.urg, b.servo, plan(9), Pose::Identity());
    EXPECT_EQ(sa.readings_mm, sb.readings_mm);
    EXPECT_EQ(sa.tilt_read_deg, sb.tilt_read_deg);
    // The n readings of a ray are independent draws, not one reading repeated.
    std::size_t differ = 0;
    for (std::size_t ray = 0; ray < sa.spec.rays(); ++ray) {
        const auto v = sa.ray_readings(ray);
        differ += v[0] != v[1] || v[1] != v[2];
    }
    EXPECT_GT(differ, sa.spec.rays() / 2);
}

TEST(Acquisition, ASensorUnpluggedMidScanLeavesAPartialScanThatIsNotFusedSilently) {
    const Scene scene = wall();
    UrgFaults unplug;
    unplug.unplugged_after = 3 * 7 + 1;  // 7 positions of 3 sweeps, then one more
    Rig r(scene, plan(21), NoiseModel::ideal(), unplug);
    const RawScan scan = acquire_scan(r.urg, r.servo, plan(21), Pose::Identity());
    EXPECT_TRUE(scan.partial());
    EXPECT_EQ(scan.spec.tilt.positions, 7);
    EXPECT_EQ(scan.planned_positions, 21);
    EXPECT_EQ(scan.readings_mm.size(), scan.spec.readings());
    EXPECT_NE(scan.stop_reason.find("URG"), std::string::npos) << scan.stop_reason;
    try {
        (void)fuse_scans(std::span(&scan, 1));
        ADD_FAILURE() << "a partial scan was fused without being allowed";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
        EXPECT_NE(std::string(e.what()).find("7 of 21"), std::string::npos) << e.what();
    }
    FuseOptions allow;
    allow.allow_partial = true;
    EXPECT_GT(fuse_scans(std::span(&scan, 1), allow).size(), 7u * 300);
}

TEST(Acquisition, AStalledServoLeavesAPartialScanAndNothingTakenIsAnError) {
    const Scene scene = wall();
    dxl::ServoFaults stall;
    stall.stall_at = dxl::ticks_of(0.5);  // blocked half a degree above level
    Rig r(scene, plan(21), NoiseModel::ideal(), {}, stall);
    const RawScan scan = acquire_scan(r.urg, r.servo, plan(21), Pose::Identity());
    EXPECT_TRUE(scan.partial());
    EXPECT_EQ(scan.spec.tilt.positions, 11);  // -40 .. 0 deg taken, 4 deg never reached
    EXPECT_NE(scan.stop_reason.find("servo"), std::string::npos) << scan.stop_reason;

    UrgFaults dead;
    dead.unplugged_after = 0;
    Rig d(scene, plan(21), NoiseModel::ideal(), dead);
    EXPECT_THROW((void)acquire_scan(d.urg, d.servo, plan(21), Pose::Identity()), DeviceError);
    // A laser the sensor cannot have is refused before the scan starts.
    ScannerSpec wide = plan(5);
    wide.laser = urg04lx_scip_769();
    EXPECT_THROW(EmulatedRig(scene, wide), Error);
}

}  // namespace
}  // namespace surfgrow::scanner
