// Raw scans, scene files, poses files and truth faces: round trips and every bad input's code.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include "support/test_support.hpp"

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/calibration_file.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"
#include "surfgrow/io/scene_file.hpp"
#include "surfgrow/io/truth_faces_file.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace {

using namespace surfgrow::scanner;
using namespace surfgrow::io;
using surfgrow::Error;
using surfgrow::ErrorCode;
using surfgrow::Mat3d;
using surfgrow::Vec3d;
using surfgrow::test::read_bytes;
using surfgrow::test::source_dir;
using surfgrow::test::TempDir;
using surfgrow::test::write_bytes;

// Plain loops: GCC 12 warns falsely about Eigen's AVX-512 reductions on 4x4 matrices.
double max_abs_diff(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
    double m = 0;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(a(r, c) - b(r, c)));
    return m;
}

template <class F>
ErrorCode code_of(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.code();
    }
    return ErrorCode::kInternal;  // "no error"
}

RawScan small_scan(bool truth) {
    ScannerSpec spec;
    spec.laser = urg04lx_scip_769();
    spec.tilt.first_deg = 10;
    spec.tilt.positions = 12;
    spec.readings_per_ray = 3;
    const Scene scene(room_corner_scene());
    RawScan r = ScanSimulator(scene, spec).simulate(scene.description().scanner.home, 4).raw;
    if (!truth) r.truth_face_id.clear();
    return r;
}

void expect_same(const RawScan& a, const RawScan& b) {
    EXPECT_EQ(a.spec, b.spec);
    EXPECT_EQ(a.pose.matrix(), b.pose.matrix());
    EXPECT_EQ(a.readings_mm, b.readings_mm);
    EXPECT_EQ(a.truth_face_id, b.truth_face_id);
    EXPECT_EQ(a.tilt_read_deg, b.tilt_read_deg);
    EXPECT_EQ(a.sensor_time_ms, b.sensor_time_ms);
    EXPECT_EQ(a.planned_positions, b.planned_positions);
    EXPECT_EQ(a.note, b.note);
    EXPECT_EQ(a.stop_reason, b.stop_reason);
}

// A scan as `surfgrow acquire` records it: read-back angles, time stamps, a note; partial when
// asked (it planned more positions than it holds).
RawScan acquired_scan(bool partial) {
    RawScan r = small_scan(false);
    for (int i = 0; i < r.spec.tilt.positions; ++i) {
        r.tilt_read_deg.push_back(r.spec.tilt.tilt_deg(i) + 0.01 * (i % 3));
        r.sensor_time_ms.push_back(static_cast<std::uint32_t>(100 * i + 16777000) & 0xffffff);
    }
    r.note = "sensor: Hokuyo / URG-04LX\nservo: id 1";
    if (partial) {
        r.planned_positions = r.spec.tilt.positions + 5;
        r.stop_reason = "URG: no good reply to GD0044072501 in 3 attempts (time-out)";
    }
    return r;
}

// FNV-1a 64 over all but the last 8 bytes, stored in them (to forge well-formed files).
void reseal(std::string& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i + 8 < bytes.size(); ++i) {
        h ^= static_cast<unsigned char>(bytes[i]);
        h *= 0x100000001b3ull;
    }
    for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + i] = static_cast<char>(h >> (8 * i));
}

TEST(RawScanFormat, RoundTripsWithAndWithoutTruth) {
    for (const bool truth : {true, false}) {
        const RawScan r = small_scan(truth);
        ASSERT_EQ(r.has_truth(), truth);
        const std::string bytes = encode_raw_scan(r);
        EXPECT_EQ(bytes.size(), kRawScanHeaderBytes + 2 * r.readings_mm.size() +
                                    (truth ? 4 * r.spec.rays() : 0) + 8);
        expect_same(decode_raw_scan(bytes, "mem"), r);
        const TempDir dir;
        write_raw_scan(dir / "scan.sgraw", r);
        expect_same(read_raw_scan(dir / "scan.sgraw"), r);
        EXPECT_EQ(read_bytes(dir / "scan.sgraw"), bytes);
    }
}

TEST(RawScanFormat, AcquisitionRecordsRoundTripAsVersionTwo) {
    for (const bool partial : {false, true}) {
        const RawScan r = acquired_scan(partial);
        EXPECT_EQ(r.partial(), partial);
        const std::string bytes = encode_raw_scan(r);
        EXPECT_EQ(bytes[8], 2) << "version";
        expect_same(decode_raw_scan(bytes, "mem"), r);
        // Every truncation and any flipped byte is refused, never a crash or a short read.
        for (std::size_t len = bytes.size() - 200; len < bytes.size(); ++len)
            EXPECT_EQ(code_of([&] { (void)decode_raw_scan(bytes.substr(0, len), "t"); }),
                      ErrorCode::kMalformedInput)
                << "length " << len;
        for (std::size_t at = bytes.size() - 120; at < bytes.size(); at += 7) {
            std::string bad = bytes;
            bad[at] = static_cast<char>(bad[at] ^ 0x21);
            EXPECT_EQ(code_of([&] { (void)decode_raw_scan(bad, "t"); }), ErrorCode::kMalformedInput)
                << "flipped byte " << at;
        }
    }
    // Without what only an acquisition records, the file stays version 1: older readers read it.
    EXPECT_EQ(encode_raw_scan(small_scan(true))[8], 1);
}

TEST(RawScanFormat, HostileVersionTwoFieldsAreRefused) {
    const RawScan r = acquired_scan(true);
    const std::string good = encode_raw_scan(r);
    // A text length claiming 4 GiB: refused by its bound, nothing allocated.
    {
        std::string bad = good;
        const std::size_t stop_len_at = good.size() - 8 - r.stop_reason.size() - 4;
        for (int i = 0; i < 4; ++i) bad[stop_len_at + i] = static_cast<char>(0xFF);
        reseal(bad);
        EXPECT_EQ(code_of([&] { (void)decode_raw_scan(bad, "t"); }), ErrorCode::kMalformedInput);
    }
    // A version-2 flag in a version-1 file, and an unknown flag: refused.
    for (const char flags : {'\x02', '\x40'}) {
        std::string bad = encode_raw_scan(small_scan(false));
        bad[12] = flags;
        reseal(bad);
        EXPECT_EQ(code_of([&] { (void)decode_raw_scan(bad, "t"); }), ErrorCode::kMalformedInput)
            << int(flags);
    }
    // Well-formed but meaningless: a NaN angle, a negative plan.
    RawScan nan_angle = acquired_scan(false);
    nan_angle.tilt_read_deg[3] = std::nan("");
    EXPECT_EQ(code_of([&] { (void)encode_raw_scan(nan_angle); }), ErrorCode::kInvalidParameter);
    {
        const std::string ok = encode_raw_scan(acquired_scan(false));
        std::string bad = ok;
        const std::size_t angle_at = ok.size() - 8 - 8 - r.note.size() - 4 * 12 - 8 * 12;
        const double nan = std::nan("");
        std::memcpy(&bad[angle_at], &nan, 8);
        reseal(bad);
        EXPECT_EQ(code_of([&] { (void)decode_raw_scan(bad, "t"); }), ErrorCode::kInvalidParameter);
    }
}

TEST(CalibrationFile, RoundTripsAndRefusesWhatItCannotUse) {
    CalibrationResult r;
    r.calibration = {0.0552, -0.31};
    r.offset_sigma_m = 0.0004;
    r.zero_estimated = true;
    r.zero_sigma_deg = 0.1;
    const std::string text = calibration_to_json(r, {"a.sgraw", "b.sgraw"});
    const Calibration c = parse_calibration_json(text, "cal.json");
    EXPECT_EQ(c.optical_offset_m, 0.0552);
    EXPECT_EQ(c.tilt_zero_deg, -0.31);
    const TempDir dir;
    write_calibration_file(dir / "c.json", r, {});
    EXPECT_EQ(read_calibration_file(dir / "c.json").optical_offset_m, 0.0552);
    EXPECT_EQ(code_of([&] { (void)read_calibration_file(dir / "none.json"); }),
              ErrorCode::kCannotOpen);
    for (const char* bad : {"", "{", "[]", R"({"format": "surfgrow-scene", "version": 1})",
                            R"({"format": "surfgrow-calibration", "version": 2,
                                "optical_offset_m": 0.04, "tilt_zero_deg": 0})",
                            R"({"format": "surfgrow-calibration", "version": 1,
                                "tilt_zero_deg": 0})",
                            R"({"format": "surfgrow-calibration", "version": 1,
                                "optical_offset_m": "40mm", "tilt_zero_deg": 0})",
                            R"({"format": "surfgrow-calibration", "version": 1,
                                "optical_offset_m": 0.04, "tilt_zero_deg": 11})",
                            R"({"format": "surfgrow-calibration", "version": 1,
                                "optical_offset_m": 1e400, "tilt_zero_deg": 0})"})
        EXPECT_EQ(code_of([&] { (void)parse_calibration_json(bad, "c.json"); }),
                  ErrorCode::kMalformedInput)
            << bad;
    // Applied: the offset replaced, the zero added to every angle the scan places rays with.
    RawScan scan = small_scan(false);
    RawScan read_back = scan;
    for (int i = 0; i < scan.spec.tilt.positions; ++i)
        read_back.tilt_read_deg.push_back(scan.spec.tilt.tilt_deg(i));
    apply_calibration(scan, c);
    apply_calibration(read_back, c);
    for (int i = 0; i < scan.spec.tilt.positions; ++i) {
        EXPECT_NEAR(scan.tilt_deg(i), read_back.tilt_deg(i), 1e-12);
        EXPECT_NEAR(scan.tilt_deg(i), small_scan(false).spec.tilt.tilt_deg(i) - 0.31, 1e-12);
    }
    EXPECT_EQ(scan.spec.optical_offset_m.z(), 0.0552);
}

TEST(RawScanFormat, FullPaperScanRoundTrips) {
    const Scene scene(ibeam_channel_scene());
    const RawScan r = ScanSimulator(scene).simulate(scene.description().scanner.home, 1).raw;
    expect_same(decode_raw_scan(encode_raw_scan(r), "mem"), r);
}

TEST(RawScanFormat, TruncatedAndCorruptedFilesAreMalformed) {
    const std::string good = encode_raw_scan(small_scan(true));
    for (const std::size_t len : {std::size_t{0}, std::size_t{7}, std::size_t{100},
                                  kRawScanHeaderBytes, good.size() / 2, good.size() - 1}) {
        EXPECT_EQ(code_of([&] { (void)decode_raw_scan(good.substr(0, len), "t"); }),
                  ErrorCode::kMalformedInput)
            << "length " << len;
    }
    EXPECT_EQ(code_of([&] { (void)decode_raw_scan(good + "x", "t"); }), ErrorCode::kMalformedInput);
    for (const std::size_t at : {std::size_t{0}, std::size_t{9}, std::size_t{13}, std::size_t{20},
                                 std::size_t{150}, good.size() / 2, good.size() - 3}) {
        std::string bad = good;
        bad[at] = static_cast<char>(bad[at] ^ 0x10);
        EXPECT_EQ(code_of([&] { (void)decode_raw_scan(bad, "t"); }), ErrorCode::kMalformedInput)
            << "flipped byte " << at;
    }
    // Header counts that would ask for gigabytes: refused before any allocation.
    std::string huge = good;
    for (int i = 0; i < 4; ++i) huge[72 + i] = static_cast<char>(0xFF);  // tilt positions = -1
    reseal(huge);
    EXPECT_EQ(code_of([&] { (void)decode_raw_scan(huge, "t"); }), ErrorCode::kMalformedInput);
    huge = good;
    huge[72] = 0x20, huge[73] = 0x4E, huge[74] = 0, huge[75] = 0;  // 20000 positions
    reseal(huge);
    EXPECT_EQ(code_of([&] { (void)decode_raw_scan(huge, "t"); }), ErrorCode::kMalformedInput);
    // A version this build does not know.
    for (const char version : {'\0', '\3', '\x7f'}) {
        std::string unknown = good;
        unknown[8] = version;
        reseal(unknown);
        EXPECT_EQ(code_of([&] { (void)decode_raw_scan(unknown, "t"); }),
                  ErrorCode::kMalformedInput);
    }
    // A ground-truth id below -1.
    std::string ids = good;
    for (int i = 0; i < 4; ++i) ids[ids.size() - 12 + i] = static_cast<char>(0xF0);
    reseal(ids);
    EXPECT_EQ(code_of([&] { (void)decode_raw_scan(ids, "t"); }), ErrorCode::kMalformedInput);
}

TEST(RawScanFormat, WellFormedButInvalidContentIsAnInvalidParameter) {
    const std::string good = encode_raw_scan(small_scan(false));
    std::string ranges = good;  // min range 5000 mm > max 4000 mm
    ranges[44] = static_cast<char>(5000 & 0xFF), ranges[45] = static_cast<char>(5000 >> 8);
    reseal(ranges);
    EXPECT_EQ(code_of([&] { (void)decode_raw_scan(ranges, "t"); }), ErrorCode::kInvalidParameter);
    std::string pose = good;  // pose(0,0) = 2.0: a scale, not a rotation
    const std::uint64_t two = std::bit_cast<std::uint64_t>(2.0);
    for (int i = 0; i < 8; ++i) pose[104 + i] = static_cast<char>(two >> (8 * i));
    reseal(pose);
    try {
        (void)decode_raw_scan(pose, "scan.sgraw");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
        EXPECT_NE(std::string(e.what()).find("scan.sgraw"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("rigid"), std::string::npos);
    }
    RawScan inconsistent = small_scan(false);
    inconsistent.readings_mm.resize(10);
    EXPECT_EQ(code_of([&] { (void)encode_raw_scan(inconsistent); }), ErrorCode::kInvalidParameter);
}

TEST(RawScanFormat, MissingFilesCannotBeOpenedAndWritesAreAtomic) {
    const TempDir dir;
    EXPECT_EQ(code_of([&] { (void)read_raw_scan(dir / "nope.sgraw"); }), ErrorCode::kCannotOpen);
    EXPECT_EQ(code_of([&] { (void)read_raw_scan(dir.path()); }), ErrorCode::kCannotOpen);
    write_bytes(dir / "junk.sgraw", "not a scan");
    EXPECT_EQ(code_of([&] { (void)read_raw_scan(dir / "junk.sgraw"); }),
              ErrorCode::kMalformedInput);
    // A scan that cannot be encoded leaves no file behind.
    RawScan bad = small_scan(false);
    bad.readings_mm.clear();
    EXPECT_THROW(write_raw_scan(dir / "bad.sgraw", bad), Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.sgraw"));
}

void expect_same(const SceneDescription& a, const SceneDescription& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.scanner.home.matrix(), b.scanner.home.matrix());
    EXPECT_EQ(a.scanner.step_m, b.scanner.step_m);
    ASSERT_EQ(a.primitives.size(), b.primitives.size());
    for (std::size_t i = 0; i < a.primitives.size(); ++i) {
        const Primitive &p = a.primitives[i], &q = b.primitives[i];
        EXPECT_EQ(p.name, q.name);
        ASSERT_EQ(p.shape.index(), q.shape.index());
        if (const auto* r = std::get_if<Rectangle>(&p.shape)) {
            const auto& s = std::get<Rectangle>(q.shape);
            EXPECT_EQ(r->center, s.center);
            EXPECT_EQ(r->u_axis, s.u_axis);
            EXPECT_EQ(r->v_axis, s.v_axis);
            EXPECT_EQ(r->half_u_m, s.half_u_m);
            EXPECT_EQ(r->half_v_m, s.half_v_m);
        } else if (const auto* b1 = std::get_if<Box>(&p.shape)) {
            const auto& b2 = std::get<Box>(q.shape);
            EXPECT_EQ(b1->center, b2.center);
            EXPECT_EQ(b1->rotation, b2.rotation);
            EXPECT_EQ(b1->half_size_m, b2.half_size_m);
        } else {
            const auto& c1 = std::get<Cylinder>(p.shape);
            const auto& c2 = std::get<Cylinder>(q.shape);
            EXPECT_EQ(c1.base, c2.base);
            EXPECT_EQ(c1.top, c2.top);
            EXPECT_EQ(c1.radius_m, c2.radius_m);
            EXPECT_EQ(c1.capped, c2.capped);
        }
    }
}

TEST(SceneFile, BuiltInScenesRoundTripExactly) {
    for (const std::string& name : builtin_scene_names()) {
        SceneDescription d = builtin_scene(name);
        if (name == "pipes") {  // add a rotated box and an open tube to cover every field
            d.primitives.push_back(
                {"tilted", Box{Vec3d(0.3, 0.2, 0.1), rotation_from_rpy(Vec3d(0.1, 0.2, 0.3)),
                               Vec3d(0.1, 0.2, 0.3)}});
            d.primitives.push_back({"", Cylinder{Vec3d::Zero(), Vec3d(0, 0, 1), 0.1, false}});
        }
        expect_same(parse_scene_json(scene_to_json(d), "mem"), d);
        const TempDir dir;
        write_scene_file(dir / "scene.json", d);
        expect_same(read_scene_file(dir / "scene.json"), d);
    }
}

TEST(SceneFile, TheShippedExampleLoads) {
    const auto path = source_dir() / "examples" / "scenes" / "single-beam.json";
    const SceneDescription d = read_scene_file(path);
    EXPECT_EQ(d.name, "single-beam");
    EXPECT_EQ(d.primitives.size(), 9u);
    const Scene s(d);
    EXPECT_EQ(s.faces().size(), 1u + 5u * 6u + 3u + 3u + 1u);
    // rpy_deg boxes are rotated; min/max boxes are not.
    EXPECT_TRUE(std::get<Box>(d.primitives[5].shape)
                    .rotation.isApprox(rotation_from_rpy(Vec3d(0, 0, 15 * M_PI / 180))));
    EXPECT_FALSE(std::get<Cylinder>(d.primitives[8].shape).capped);
    EXPECT_NEAR((d.scanner.home.translation() - Vec3d(0, 0, 0.9)).norm(), 0.0, 1e-12);
    // And it can be scanned.
    const SimulatedScan scan = ScanSimulator(s).simulate(d.scanner.home, 1);
    std::size_t returns = 0;
    for (const auto v : scan.raw.readings_mm) returns += v != 0 ? 1 : 0;
    EXPECT_GT(returns, 100000u);
}

TEST(SceneFile, BadScenesGiveTheirCodes) {
    const std::string head = R"({"format": "surfgrow-scene", "version": 1, "primitives": [)";
    auto code = [&](const std::string& text) {
        return code_of([&] { (void)parse_scene_json(text, "s.json"); });
    };
    EXPECT_EQ(code(head + "]}"), ErrorCode::kInternal);  // an empty scene is fine
    EXPECT_EQ(code("{"), ErrorCode::kMalformedInput);
    EXPECT_EQ(code("[]"), ErrorCode::kMalformedInput);
    EXPECT_EQ(code(R"({"version": 1, "primitives": []})"), ErrorCode::kMalformedInput);
    EXPECT_EQ(code(R"({"format": "ply", "version": 1, "primitives": []})"),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code(R"({"format": "surfgrow-scene", "version": 2, "primitives": []})"),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code(head + R"(], "extra": 1})"), ErrorCode::kMalformedInput);
    EXPECT_EQ(code(head + R"({"type": "sphere", "radius": 1}]})"), ErrorCode::kMalformedInput);
    EXPECT_EQ(code(head + R"({"type": "box", "centre": [0,0,0], "size": [1,1,1]}]})"),
              ErrorCode::kMalformedInput);  // misspelt key
    EXPECT_EQ(code(head + R"({"type": "box", "center": [0,0], "size": [1,1,1]}]})"),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code(head + R"({"type": "box", "center": [0,0,"a"], "size": [1,1,1]}]})"),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code(head + R"({"type": "box", "min": [0,0,0], "max": [1,1,1], "size": [1,1,1]}]})"),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code(head + R"({"type": "cylinder", "base": [0,0,0], "top": [0,0,1]}]})"),
              ErrorCode::kMalformedInput);  // no radius
    EXPECT_EQ(
        code(head + R"({"type": "cylinder", "base": [0,0,0], "top": [0,0,1], "radius": -1}]})"),
        ErrorCode::kInvalidParameter);
    EXPECT_EQ(code(head + R"({"type": "box", "min": [0,0,0], "max": [1,-1,1]}]})"),
              ErrorCode::kInvalidParameter);
    EXPECT_EQ(code(head + R"({"type": "rectangle", "center": [0,0,0], "u_axis": [1,0,0],
                              "v_axis": [1,1,0], "size": [1,1]}]})"),
              ErrorCode::kInvalidParameter);
    EXPECT_EQ(code(head + R"({"type": "box", "center": [0,0,0], "size": [1,1,1],
                              "rotation": [[2,0,0],[0,1,0],[0,0,1]]}]})"),
              ErrorCode::kInvalidParameter);
    EXPECT_EQ(
        code(head +
             R"(], "scanner": {"pose": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,-1,0],[0,0,0,1]]}}})"),
        ErrorCode::kInvalidParameter);  // a reflection
    EXPECT_EQ(code(std::string(10000, '[') + std::string(10000, ']')), ErrorCode::kMalformedInput);
    // Messages name the file and the primitive.
    try {
        (void)parse_scene_json(head + R"({"type": "cylinder", "name": "bolt", "base": [0,0,0],
                                          "top": [0,0,1], "radius": 0}]})",
                               "s.json");
        FAIL();
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("s.json"), std::string::npos) << m;
        EXPECT_NE(m.find("bolt"), std::string::npos) << m;
    }
    const TempDir dir;
    EXPECT_EQ(code_of([&] { (void)read_scene_file(dir / "missing.json"); }),
              ErrorCode::kCannotOpen);
}

TEST(PosesFile, TextWithMatricesRpyAndComments) {
    const std::string text =
        "# three poses\n"
        "1 0 0 0.5  0 1 0 0  0 0 1 1.45  0 0 0 1   # a matrix\n"
        "\n"
        "  0.5, 0, 1.45, 0, -90, 0\r\n"
        "+1.0 2 3 90 0 0\n";
    const auto poses = parse_poses_text(text, "p.txt");
    ASSERT_EQ(poses.size(), 3u);
    EXPECT_EQ(poses[0].translation(), Vec3d(0.5, 0, 1.45));
    EXPECT_TRUE(poses[0].linear().isIdentity(0.0));
    EXPECT_NEAR((poses[1].linear() * Vec3d::UnitX() - Vec3d::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((poses[2].linear() * Vec3d::UnitY() - Vec3d::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_EQ(poses[2].translation(), Vec3d(1, 2, 3));
}

TEST(PosesFile, RoundTripsExactlyAsTextAndJson) {
    const std::vector<Pose> poses = scan_poses(ibeam_channel_scene().scanner, 3);
    const TempDir dir;
    write_poses_file(dir / "poses.txt", poses);
    const auto back = read_poses_file(dir / "poses.txt");
    ASSERT_EQ(back.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_LE(max_abs_diff(back[i].matrix(), poses[i].matrix()), 1e-15);
    std::string json = "{\"poses\": [";
    for (std::size_t i = 0; i < 3; ++i) json += (i ? "," : "") + pose_to_json(poses[i]).dump();
    json += "]}";
    write_bytes(dir / "poses.json", json);
    const auto from_json = read_poses_file(dir / "poses.json");
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(from_json[i].matrix(), poses[i].matrix());
    const auto forms = parse_poses_json(
        R"([[0,0,1,0,-90,0], {"position": [0,0,1], "rpy_deg": [0,-90,0]},
            {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}])",
        "p.json");
    ASSERT_EQ(forms.size(), 3u);
    EXPECT_LE(max_abs_diff(forms[0].matrix(), forms[1].matrix()), 1e-15);
    EXPECT_EQ(max_abs_diff(forms[2].matrix(), Eigen::Matrix4d::Identity()), 0.0);
}

TEST(PosesFile, BadPosesGiveTheirCodesAndLines) {
    auto text_code = [](const std::string& t) {
        return code_of([&] { (void)parse_poses_text(t, "p.txt"); });
    };
    EXPECT_EQ(text_code(""), ErrorCode::kMalformedInput);
    EXPECT_EQ(text_code("# nothing\n\n"), ErrorCode::kMalformedInput);
    EXPECT_EQ(text_code("1 2 3 4 5\n"), ErrorCode::kMalformedInput);
    EXPECT_EQ(text_code("1 2 3 4 5 six\n"), ErrorCode::kMalformedInput);
    EXPECT_EQ(text_code("1 2 3 4 5 6 7\n"), ErrorCode::kMalformedInput);
    EXPECT_EQ(text_code("2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1\n"), ErrorCode::kInvalidParameter);
    EXPECT_EQ(text_code("-1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"), ErrorCode::kInvalidParameter);
    EXPECT_EQ(text_code("1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\n"), ErrorCode::kInvalidParameter);
    EXPECT_EQ(text_code("0 0 nan 0 0 0\n"), ErrorCode::kInvalidParameter);
    try {
        (void)parse_poses_text("0 0 0 0 0 0\n# ok\n1 2 3\n", "p.txt");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("p.txt:3"), std::string::npos) << e.what();
    }
    auto json_code = [](const std::string& t) {
        return code_of([&] { (void)parse_poses_json(t, "p.json"); });
    };
    EXPECT_EQ(json_code("{"), ErrorCode::kMalformedInput);
    EXPECT_EQ(json_code("[]"), ErrorCode::kMalformedInput);
    EXPECT_EQ(json_code(R"({"pose": []})"), ErrorCode::kMalformedInput);
    EXPECT_EQ(json_code(R"([{"position": [0,0,0]}])"), ErrorCode::kMalformedInput);
    EXPECT_EQ(json_code(R"([{"matrix": [[1,0,0],[0,1,0],[0,0,1]]}])"), ErrorCode::kMalformedInput);
    EXPECT_EQ(json_code(R"([{"matrix": [[1,1,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}])"),
              ErrorCode::kInvalidParameter);
    const TempDir dir;
    EXPECT_EQ(code_of([&] { (void)read_poses_file(dir / "none.txt"); }), ErrorCode::kCannotOpen);
}

TEST(TruthFacesFile, RoundTripsTheIBeamChannelFaces) {
    const Scene scene(ibeam_channel_scene());
    const TempDir dir;
    write_truth_faces(dir / "truth.json", scene);
    const auto faces = read_truth_faces(dir / "truth.json");
    ASSERT_EQ(faces.size(), scene.faces().size());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Face &a = faces[i], &b = scene.faces()[i];
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.primitive, b.primitive);
        EXPECT_EQ(a.kind, b.kind);
        EXPECT_EQ(a.center, b.center);
        EXPECT_EQ(a.normal, b.normal);
        EXPECT_EQ(a.half_u_m, b.half_u_m);
        EXPECT_EQ(a.half_v_m, b.half_v_m);
        if (a.kind == FaceKind::kRectangle) {
            EXPECT_EQ(a.u_axis, b.u_axis);
            EXPECT_NEAR((a.u_axis.cross(a.v_axis) - a.normal).norm(), 0.0, 1e-12);
        }
    }
    EXPECT_EQ(code_of([&] { (void)parse_truth_faces_json(R"({"format": "x"})", "t"); }),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code_of([&] {
                  (void)parse_truth_faces_json(
                      R"({"format": "surfgrow-truth-faces", "version": 1,
                          "faces": [{"id": 3, "primitive": 0, "kind": "disc"}]})",
                      "t");
              }),
              ErrorCode::kMalformedInput);
}

}  // namespace
