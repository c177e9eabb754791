// End-to-end tests of `surfgrow acquire`: a whole scan of the I-beam channel through the emulated
// URG-04LX and servo behind pseudo-terminals, then scan2cloud, grow and eval as a user runs them;
// every fault the emulator injects gives a retry or a partial scan that is kept and marked,
// never silently fused; bad arguments are refused before a device is touched.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/raw_scan_format.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;
using test::CliRun;

constexpr int kExitDeviceFailed = 11;  // README, "When something is wrong"

CliRun surfgrow(const std::string& args) {
    return test::run_surfgrow(args);
}
std::string q(const fs::path& p) {
    return test::quoted(p);
}

// A short plan for the fault cases: 21 positions, 3 readings, quick time-outs.
const std::string kShort = " --tilt -10deg:10deg:1deg --readings 3 --timeout 100ms ";

TEST(CliAcquire, AWholeEmulatedScanOfTheChannelGrowsAsWellAsASimulatedOne) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    const test::TempDir tmp;
    const fs::path scans = tmp / "scans";
    CliRun r = surfgrow(cat({"acquire --emulate ibeam-channel -o ", q(scans)}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("361 tilt positions x 682 steps x 5 readings"), std::string::npos)
        << r.out;
    const scanner::RawScan scan = io::read_raw_scan(scans / "scan-000.sgraw");
    EXPECT_FALSE(scan.partial());
    ASSERT_EQ(scan.tilt_read_deg.size(), 361u);
    // The servo reports whole ticks (360/4096 deg): the angles recorded are those, not the plan.
    for (int i = 0; i < 361; ++i) {
        EXPECT_NEAR(scan.tilt_read_deg[i], scan.spec.tilt.tilt_deg(i), 0.5 * 360 / 4096 + 1e-9);
        const double ticks = scan.tilt_read_deg[i] * 4096 / 360;
        EXPECT_NEAR(ticks, std::round(ticks), 1e-9);
    }
    EXPECT_TRUE(scan.has_truth());
    EXPECT_NE(scan.note.find("URG-04LX"), std::string::npos) << scan.note;
    EXPECT_TRUE(fs::exists(scans / "scene.json"));

    // The same seed, the same bytes (the emulation is deterministic); a second acquisition into
    // the folder becomes the next scan.
    r = surfgrow(cat({"acquire --emulate ibeam-channel -q -o ", q(scans)}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(test::read_bytes(scans / "scan-000.sgraw"),
              test::read_bytes(scans / "scan-001.sgraw"));
    fs::remove(scans / "scan-001.sgraw");

    // Then as with any scan: fused, grown and scored against the scene's truth.
    r = surfgrow(cat({"scan2cloud ", q(scans), " -q -o ", q(scans / "cloud.ply")}));
    ASSERT_EQ(r.code, 0) << r.out;
    r = surfgrow(cat({"grow ", q(scans / "cloud.ply"), " -q --no-picture -o ", q(tmp / "out")}));
    ASSERT_EQ(r.code, 0) << r.out;
    r = surfgrow(cat({"eval ", q(tmp / "out"), " --truth ", q(scans), " -q"}));
    ASSERT_EQ(r.code, 0) << r.out;
    const auto m = nlohmann::json::parse(test::read_bytes(tmp / "out" / "eval.json"))["metrics"];
    EXPECT_GE(m["registered_planar"].get<double>(), 0.99) << r.out;
    EXPECT_LE(m["normal_median"].get<double>(), 1.0) << r.out;
    EXPECT_LE(m["planes_normal_p95"].get<double>(), 2.0) << r.out;
    EXPECT_LE(m["normal_over_45"].get<double>(), 0.01) << r.out;
}

TEST(CliAcquire, DamagedAndLostRepliesAreAskedForAgain) {
    const test::TempDir tmp;
    const CliRun r = surfgrow(cat({"acquire --emulate room-corner", kShort,
                                   "--emulate-fault urg-corrupt=4 --emulate-fault urg-drop=9 "
                                   "--emulate-fault urg-garble=12 --emulate-fault servo-drop=3 "
                                   "--emulate-fault servo-corrupt=8 -o ",
                                   q(tmp / "a.sgraw")}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("(3 retries)"), std::string::npos) << r.out;  // the URG's
    EXPECT_FALSE(io::read_raw_scan(tmp / "a.sgraw").partial());
}

TEST(CliAcquire, ALaggingServoIsRecordedWhereItStopped) {
    const test::TempDir tmp;
    const CliRun r = surfgrow(cat({"acquire --emulate room-corner", kShort,
                                   "--emulate-fault servo-lag=0.5deg -q -o ", q(tmp / "a.sgraw")}));
    ASSERT_EQ(r.code, 0) << r.out;
    const scanner::RawScan scan = io::read_raw_scan(tmp / "a.sgraw");
    // 0.5 deg is 6 of the servo's ticks (360/4096 deg); each goal is rounded to a tick.
    const double tick = 360.0 / 4096;
    for (int i = 0; i < scan.spec.tilt.positions; ++i)
        EXPECT_NEAR(scan.tilt_read_deg[i] - scan.spec.tilt.tilt_deg(i), 6 * tick, tick / 2 + 1e-9);
}

TEST(CliAcquire, ADeviceFailingMidScanLeavesAPartialScanThatScan2CloudRefuses) {
    const test::TempDir tmp;
    // The sensor unplugged after 10 positions' sweeps; the servo blocked at 3 deg.
    for (const std::string fault : {"urg-unplug=30", "servo-stall=3deg"}) {
        const fs::path file = tmp / (fault.substr(0, 3) + ".sgraw");
        CliRun r = surfgrow(cat(
            {"acquire --emulate room-corner", kShort, "--emulate-fault ", fault, " -o ", q(file)}));
        EXPECT_EQ(r.code, kExitDeviceFailed) << r.out;
        EXPECT_NE(r.out.find("partial"), std::string::npos) << r.out;
        const scanner::RawScan scan = io::read_raw_scan(file);
        EXPECT_TRUE(scan.partial());
        EXPECT_EQ(scan.planned_positions, 21);
        EXPECT_EQ(scan.spec.tilt.positions, fault[0] == 'u' ? 10 : 14);
        EXPECT_NE(scan.stop_reason.find(fault[0] == 'u' ? "URG" : "servo"), std::string::npos)
            << scan.stop_reason;
        r = surfgrow(cat({"scan2cloud ", q(file), " -o ", q(tmp / "c.ply")}));
        EXPECT_EQ(r.code, 3) << r.out;
        EXPECT_NE(r.out.find("--allow-partial"), std::string::npos) << r.out;
        EXPECT_FALSE(fs::exists(tmp / "c.ply"));
        r = surfgrow(cat({"scan2cloud ", q(file), " --allow-partial -q -o ", q(tmp / "c.ply")}));
        EXPECT_EQ(r.code, 0) << r.out;
        fs::remove(tmp / "c.ply");
    }
    // Unplugged from the start: nothing is taken, nothing written.
    const CliRun r = surfgrow(cat({"acquire --emulate room-corner", kShort,
                                   "--emulate-fault urg-unplug=0 -o ", q(tmp / "none.sgraw")}));
    EXPECT_EQ(r.code, kExitDeviceFailed) << r.out;
    EXPECT_NE(r.out.find("nothing was written"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(tmp / "none.sgraw"));
}

TEST(CliAcquire, BadArgumentsAreRefusedBeforeADeviceIsTouched) {
    const test::TempDir tmp;
    const std::string out = " -o " + q(tmp / "x.sgraw");
    const struct {
        const char* args;
        int code;
        const char* says;
    } cases[] = {
        {"--emulate room-corner --tilt -10:10:1", 2, "no unit"},
        {"--emulate room-corner --tilt 10deg:-10deg:1deg", 3, "FIRST <= LAST"},
        {"--emulate room-corner --tilt -10deg:10deg", 2, "FIRST:LAST:STEP"},
        {"--emulate room-corner --tilt -90deg:90deg:0.001deg", 3, "at most 20000"},
        {"--emulate room-corner --readings 0", 3, "readings"},
        {"--emulate room-corner --servo-id 300", 3, "--servo-id"},
        {"--emulate room-corner --timeout 5", 2, "--timeout"},
        {"--emulate room-corner --emulate-fault urg-melt=1", 2, "unknown fault"},
        {"--emulate-fault urg-drop=1", 2, "needs --emulate"},
        {"--emulate no-such-scene", 3, "no-such-scene"},
        {"--port /no/such/port", 4, "/no/such/port"},
        {"--port /dev/null", 4, "not a serial port"},
    };
    for (const auto& c : cases) {
        const CliRun r = surfgrow(cat({"acquire ", c.args, out}));
        EXPECT_EQ(r.code, c.code) << c.args << ": " << r.out;
        EXPECT_NE(r.out.find(c.says), std::string::npos) << c.args << ": " << r.out;
        EXPECT_FALSE(fs::exists(tmp / "x.sgraw")) << c.args;
    }
    const CliRun r = surfgrow("acquire --emulate room-corner -o /no/such/folder/a.sgraw");
    EXPECT_EQ(r.code, 7) << r.out;
    EXPECT_NE(r.out.find("nothing was scanned"), std::string::npos) << r.out;
}

TEST(CliCalibrate, AWrongOpticalOffsetIsFoundAndScan2CloudAppliesIt) {
    const test::TempDir tmp;
    const fs::path scans = tmp / "scans";
    // The bracket holds the laser 55 mm above the axis; the scan is recorded with 40 mm.
    CliRun r =
        surfgrow(cat({"acquire --emulate room-corner --emulate-offset 55mm -q -o ", q(scans)}));
    ASSERT_EQ(r.code, 0) << r.out;
    r = surfgrow(cat({"calibrate ", q(scans)}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("servo zero not estimated"), std::string::npos) << r.out;
    const auto c = nlohmann::json::parse(test::read_bytes(scans / "calibration.json"));
    const double offset = c["optical_offset_m"].get<double>();
    const double sigma = c["optical_offset_sigma_m"].get<double>();
    EXPECT_NEAR(offset, 0.055, 0.002) << r.out;
    EXPECT_LT(std::abs(offset - 0.055), 4 * sigma + 0.0005) << r.out;
    EXPECT_LT(c["surface"]["rms_after_m"].get<double>(),
              c["surface"]["rms_before_m"].get<double>());
    EXPECT_LT(c["surface"]["bow_m"].get<double>(), 0.002);  // the room's wall is flat
    // scan2cloud of the folder converts with it, and says so; `none` leaves the scans as they are.
    r = surfgrow(cat({"scan2cloud ", q(scans), " -o ", q(tmp / "a.ply")}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("calibrated by"), std::string::npos) << r.out;
    r = surfgrow(cat({"scan2cloud ", q(scans), " --calibration none -o ", q(tmp / "b.ply")}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("calibrated by"), std::string::npos) << r.out;
    EXPECT_NE(test::read_bytes(tmp / "a.ply"), test::read_bytes(tmp / "b.ply"));

    // What it cannot use is refused by name.
    test::write_bytes(tmp / "bad.json", R"({"format": "surfgrow-calibration", "version": 1,
        "optical_offset_m": 5, "tilt_zero_deg": 0})");
    r = surfgrow(cat({"scan2cloud ", q(scans), " --calibration ", q(tmp / "bad.json"), " -o ",
                      q(tmp / "c.ply")}));
    EXPECT_EQ(r.code, 6) << r.out;
    EXPECT_NE(r.out.find("optical_offset_m"), std::string::npos) << r.out;
    r = surfgrow(cat({"calibrate ", q(scans / "scan-000.sgraw")}));
    EXPECT_EQ(r.code, 2) << r.out;
    r = surfgrow(cat({"calibrate ", q(tmp / "nothing-here"), " -o ", q(tmp / "x.json")}));
    EXPECT_EQ(r.code, 4) << r.out;
    // A scan whose largest plane cannot tell the offset (the stairs: +- 100 mm) writes nothing
    // that scan2cloud would then apply, and says which scans and why.
    const fs::path stairs = tmp / "stairs";
    ASSERT_EQ(surfgrow(cat({"scan --scene stairs --poses 1 -q -o ", q(stairs)})).code, 0);
    r = surfgrow(cat({"calibrate ", q(stairs)}));
    EXPECT_EQ(r.code, 3) << r.out;
    EXPECT_NE(r.out.find(stairs.string() + ": calibrate: the largest plane in the scans cannot "
                                           "tell the optical offset"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(stairs / "calibration.json"));
}

TEST(CliMap, ScansArrivingInAFolderAreMappedAsTheyCome) {
    const test::TempDir tmp;
    const fs::path scans = tmp / "scans";
    fs::create_directories(scans);
    // The mapper waits for scans; the scanner takes two, from two places along the corner.
    CliRun watched;
    std::thread mapper([&] {
        // Stops at the second scan, however slowly they come (a sanitizer build).
        watched = surfgrow(cat({"map --watch ", q(scans), " --scans 2 --idle 120s --no-picture -o ",
                                q(tmp / "live")}));
    });
    for (const char* pose : {"0/2", "1/2"}) {
        const CliRun r =
            surfgrow(cat({"acquire --emulate room-corner --pose ", pose, " -q -o ", q(scans)}));
        EXPECT_EQ(r.code, 0) << r.out;
    }
    mapper.join();
    ASSERT_EQ(watched.code, 0) << watched.out;
    EXPECT_NE(watched.out.find("scan 0 (scan-000.sgraw)"), std::string::npos) << watched.out;
    EXPECT_NE(watched.out.find("scan 1 (scan-001.sgraw)"), std::string::npos) << watched.out;
    EXPECT_NE(watched.out.find("joined the map"), std::string::npos) << watched.out;

    // The same scans given at once: the same map, byte for byte.
    CliRun r =
        surfgrow(cat({"map ", q(scans), " -q --no-picture --coverage-csv -o ", q(tmp / "given")}));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* file :
         {"surfaces.json", "labels.bin", "planes.json", "coverage.json", "coverage.ply"}) {
        EXPECT_TRUE(fs::exists(tmp / "live" / file)) << file;
        EXPECT_TRUE(test::read_bytes(tmp / "live" / file) == test::read_bytes(tmp / "given" / file))
            << file;
    }
    EXPECT_FALSE(fs::exists(tmp / "live" / "coverage.csv"));  // the text goals only on request
    EXPECT_TRUE(fs::exists(tmp / "given" / "coverage.csv"));
    // And scored like any result, against the fused cloud of the same scans.
    r = surfgrow(cat({"scan2cloud ", q(scans), " -q -o ", q(scans / "cloud.ply")}));
    ASSERT_EQ(r.code, 0) << r.out;
    r = surfgrow(cat({"eval ", q(tmp / "given"), " --truth ", q(scans),
                      " -q --require 'registered_planar>=0.98'"}));
    EXPECT_EQ(r.code, 0) << r.out;

    // Nothing to map, a partial scan, raw scans in another unit: refused.
    EXPECT_EQ(surfgrow(cat({"map -o ", q(tmp / "x")})).code, 2);
    EXPECT_EQ(surfgrow(cat({"map ", q(scans), " --units mm -o ", q(tmp / "x")})).code, 2);
    r = surfgrow(cat({"acquire --emulate room-corner", kShort, "--emulate-fault urg-unplug=30 -o ",
                      q(tmp / "p")}));
    EXPECT_EQ(r.code, kExitDeviceFailed) << r.out;
    r = surfgrow(cat({"map ", q(tmp / "p"), " -o ", q(tmp / "x")}));
    EXPECT_EQ(r.code, 3) << r.out;
    EXPECT_NE(r.out.find("--allow-partial"), std::string::npos) << r.out;
}

TEST(CliDemo, EmulatedScansMappedOneByOneGiveTheDemosFolder) {
    const test::TempDir tmp;
    const CliRun r = surfgrow(cat({"demo --emulate --poses 2 -q -o ", q(tmp / "demo")}));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* file :
         {"surfaces.ply", "surfaces.json", "planes.json", "coverage.json", "coverage.ply",
          "occupancy.ply", "environment.bt", "surfaces.png", "corner.png", "eval.json",
          "scan/scan-000.sgraw", "scan/scan-001.sgraw", "scan/scene.json"})
        EXPECT_TRUE(fs::exists(tmp / "demo" / file)) << file;
    const auto m = nlohmann::json::parse(test::read_bytes(tmp / "demo" / "eval.json"))["metrics"];
    EXPECT_GE(m["registered_planar"].get<double>(), 0.99);
    EXPECT_LE(m["normal_median"].get<double>(), 1.0);
    EXPECT_LE(m["planes_normal_p95"].get<double>(), 2.0);
}

}  // namespace
}  // namespace surfgrow
