// End-to-end tests of `surfgrow scan`, `scan2cloud`, `eval` and `demo`: the real binary.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace surfgrow {
namespace {

// The exit status of a bound that does not hold (README, "When something is wrong").
constexpr int kExitRequirementFailed = 9;

namespace fs = std::filesystem;

using test::CliRun;

// Runs the CLI with arguments (already shell-quoted where needed); `env` goes before it.
CliRun surfgrow(const std::string& args, const std::string& env = "") {
    return test::run_surfgrow(args, env);
}

std::string q(const fs::path& p) {
    return test::quoted(p);
}

nlohmann::json read_json(const fs::path& file) {
    return nlohmann::json::parse(test::read_bytes(file));
}

// One scan of the room corner from two poses: small and quick, with every kind of output.
class CliScan : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir();
        const CliRun r =
            surfgrow(cat({"scan --scene room-corner --poses 2 --seed 3 -o ", q(scan_dir())}));
        ASSERT_EQ(r.code, 0) << r.out;
    }
    static void TearDownTestSuite() { delete dir_; }
    static fs::path scan_dir() { return dir_->path() / "scan"; }
    static test::TempDir* dir_;
    test::TempDir tmp_;
};
test::TempDir* CliScan::dir_ = nullptr;

TEST_F(CliScan, WritesRawScansFusedCloudTruthSceneAndPoses) {
    for (const char* f : {"scan-000.sgraw", "scan-001.sgraw", "cloud.ply", "truth-faces.json",
                          "scene.json", "poses.txt", "scan.json"})
        EXPECT_TRUE(fs::is_regular_file(scan_dir() / f)) << f;
    EXPECT_FALSE(fs::exists(scan_dir() / "scan-002.sgraw"));
    const PointCloud cloud = io::read_cloud(scan_dir() / "cloud.ply");
    ASSERT_TRUE(cloud.has_labels());
    ASSERT_TRUE(cloud.has_scan_index());
    ASSERT_EQ(cloud.scan_origins.size(), 2u);
    const auto manifest = read_json(scan_dir() / "scan.json");
    EXPECT_EQ(manifest.at("points").get<std::size_t>(), cloud.size());
    EXPECT_EQ(manifest.at("scans").size(), 2u);
    EXPECT_EQ(manifest.at("scene"), "room-corner");
    const scanner::RawScan raw = io::read_raw_scan(scan_dir() / "scan-001.sgraw");
    EXPECT_TRUE(raw.has_truth());
    EXPECT_EQ(raw.pose.translation(), cloud.scan_origins[1]);
}

TEST_F(CliScan, SameSeedSameBytesOnOneThread) {
    ASSERT_EQ(surfgrow(cat({"scan --scene room-corner --poses 2 --seed 3 -q -o ",
                            q(tmp_.path() / "again")}),
                       "OMP_NUM_THREADS=1 ")
                  .code,
              0);
    for (const char* f : {"scan-000.sgraw", "scan-001.sgraw", "cloud.ply", "scan.json"})
        EXPECT_EQ(test::read_bytes(tmp_.path() / "again" / f), test::read_bytes(scan_dir() / f))
            << f;
}

TEST_F(CliScan, Scan2CloudOfTheRawScansIsTheFusedCloud) {
    const fs::path raw0 = scan_dir() / "scan-000.sgraw", raw1 = scan_dir() / "scan-001.sgraw";
    const CliRun with_poses =
        surfgrow(cat({"scan2cloud ", q(raw0), " ", q(raw1), " --poses ",
                      q(scan_dir() / "poses.txt"), " -o ", q(tmp_.path() / "a.ply")}));
    ASSERT_EQ(with_poses.code, 0) << with_poses.out;
    EXPECT_EQ(test::read_bytes(tmp_.path() / "a.ply"), test::read_bytes(scan_dir() / "cloud.ply"));
    // Without --poses each raw scan's own pose is used: the same cloud.
    ASSERT_EQ(
        surfgrow(cat({"scan2cloud ", q(raw0), " ", q(raw1), " -o ", q(tmp_.path() / "b.ply")}))
            .code,
        0);
    EXPECT_EQ(test::read_bytes(tmp_.path() / "b.ply"), test::read_bytes(scan_dir() / "cloud.ply"));
    // A stricter range limit keeps fewer points.
    ASSERT_EQ(
        surfgrow(cat({"scan2cloud ", q(raw0), " --max-range 1.2m -o ", q(tmp_.path() / "c.ply")}))
            .code,
        0);
    EXPECT_LT(io::read_cloud(tmp_.path() / "c.ply").size(),
              io::read_cloud(scan_dir() / "cloud.ply").size() / 2);
}

// --veil-angle drops mixed pixels (off by default) and says how many; outside 0..45 degrees it
// is a usage error that writes nothing.
TEST_F(CliScan, Scan2CloudDropsMixedPixelsWhenAsked) {
    // The pipes in front of their wall: blends fill the depth gaps behind them (the room corner
    // above has no depth edges).
    ASSERT_EQ(surfgrow(cat({"scan --scene pipes --poses 1 -q -o ", q(tmp_.path() / "pipes")})).code,
              0);
    const fs::path raw0 = tmp_.path() / "pipes" / "scan-000.sgraw";
    const CliRun all = surfgrow(cat({"scan2cloud ", q(raw0), " -o ", q(tmp_.path() / "f.ply")}));
    ASSERT_EQ(all.code, 0) << all.out;
    EXPECT_EQ(all.out.find("mixed pixels"), std::string::npos) << all.out;
    const CliRun veil =
        surfgrow(cat({"scan2cloud ", q(raw0), " --veil-angle 10 -o ", q(tmp_.path() / "g.ply")}));
    ASSERT_EQ(veil.code, 0) << veil.out;
    const std::size_t kept = io::read_cloud(tmp_.path() / "g.ply").size();
    const std::size_t every = io::read_cloud(tmp_.path() / "f.ply").size();
    ASSERT_LT(kept, every);
    EXPECT_NE(veil.out.find(cat({"; ", std::to_string(every - kept), " mixed pixels dropped"})),
              std::string::npos)
        << veil.out;
    const CliRun bad =
        surfgrow(cat({"scan2cloud ", q(raw0), " --veil-angle 50 -o ", q(tmp_.path() / "h.ply")}));
    EXPECT_EQ(bad.code, static_cast<int>(ErrorCode::kUsage)) << bad.out;
    EXPECT_FALSE(fs::exists(tmp_.path() / "h.ply"));
}

// The folder `surfgrow scan -o` wrote stands for its raw scans, in scan order (the README's
// `surfgrow scan2cloud scan/ -o cloud.ply`); a folder without any is refused by name.
TEST_F(CliScan, Scan2CloudOfAScanFolderIsTheFusedCloud) {
    const CliRun run =
        surfgrow(cat({"scan2cloud ", q(scan_dir()), " -o ", q(tmp_.path() / "d.ply")}));
    ASSERT_EQ(run.code, 0) << run.out;
    EXPECT_EQ(test::read_bytes(tmp_.path() / "d.ply"), test::read_bytes(scan_dir() / "cloud.ply"));
    fs::create_directories(tmp_.path() / "empty");
    const CliRun empty =
        surfgrow(cat({"scan2cloud ", q(tmp_.path() / "empty"), " -o ", q(tmp_.path() / "e.ply")}));
    EXPECT_EQ(empty.code, static_cast<int>(ErrorCode::kCannotOpen)) << empty.out;
    EXPECT_NE(empty.out.find("no raw scans"), std::string::npos) << empty.out;
    EXPECT_FALSE(fs::exists(tmp_.path() / "e.ply"));
}

TEST_F(CliScan, OtherPosesMoveTheCloud) {
    test::write_bytes(tmp_.path() / "moved.txt",
                      "0.5 0.5 1.6 0 0 45\n0.75 0.25 1.6 0 0 45\n");  // 1 m higher
    ASSERT_EQ(surfgrow(cat({"scan2cloud ", q(scan_dir() / "scan-000.sgraw"), " ",
                            q(scan_dir() / "scan-001.sgraw"), " --poses ",
                            q(tmp_.path() / "moved.txt"), " -o ", q(tmp_.path() / "m.ply")}))
                  .code,
              0);
    const PointCloud a = io::read_cloud(scan_dir() / "cloud.ply");
    const PointCloud m = io::read_cloud(tmp_.path() / "m.ply");
    ASSERT_EQ(a.size(), m.size());
    EXPECT_NEAR(m.points[100].z() - a.points[100].z(), 1.0, 1e-5);
    EXPECT_NEAR(m.scan_origins[0].z(), 1.6, 1e-12);
}

TEST_F(CliScan, GrowTurnsNormalsTowardEachPointsOwnScanAndEvalMeasuresIt) {
    const fs::path out = tmp_.path() / "out";
    const CliRun g = surfgrow(
        cat({"grow ", q(scan_dir() / "cloud.ply"), " -o ", q(out), " --no-picture --mu-max 48mm"}));
    ASSERT_EQ(g.code, 0) << g.out;
    EXPECT_EQ(read_json(out / "surfaces.json").at("summary").at("orientation"), "scan_origins");

    const CliRun e = surfgrow(cat({"eval ", q(out), " --truth ", q(scan_dir()),
                                   " --require 'registered_workspace>=99%,normal_median<=3'"}));
    ASSERT_EQ(e.code, 0) << e.out;
    EXPECT_NE(e.out.find("eval: "), std::string::npos) << e.out;
    EXPECT_NE(e.out.find("range band"), std::string::npos) << e.out;
    const auto j = read_json(out / "eval.json");
    EXPECT_GE(j.at("metrics").at("registered_workspace").get<double>(), 0.99);
    EXPECT_LE(j.at("metrics").at("normal_median").get<double>(), 3.0);
    EXPECT_GE(j.at("metrics").at("facing_sensor").get<double>(), 0.99);
    EXPECT_EQ(j.at("requirements").size(), 2u);
    EXPECT_FALSE(j.at("bands").empty());

    // A bound that does not hold: exit code 9, the evaluation still written, the bound named.
    fs::remove(out / "eval.json");
    const CliRun strict = surfgrow(
        cat({"eval ", q(out), " --truth ", q(scan_dir()), " --require 'normal_p95<=0.1'"}));
    EXPECT_EQ(strict.code, kExitRequirementFailed) << strict.out;
    EXPECT_NE(strict.out.find("normal_p95<=0.1"), std::string::npos) << strict.out;
    EXPECT_TRUE(fs::exists(out / "eval.json"));
    EXPECT_EQ(read_json(out / "eval.json").at("requirements").at(0).at("met"), false);

    // A bad bound is a usage error found before anything is read or written.
    fs::remove(out / "eval.json");
    const CliRun bad =
        surfgrow(cat({"eval ", q(out), " --truth ", q(scan_dir()), " --require 'speed>=1'"}));
    EXPECT_EQ(bad.code, static_cast<int>(ErrorCode::kUsage)) << bad.out;
    EXPECT_FALSE(fs::exists(out / "eval.json"));
}

TEST_F(CliScan, OnTheTiltAxisWithPoseErrorsAndTheEvalShowsTheTail) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    // The laser on the tilt axis and fused with recorded poses 2 mm and 0.1 degree off: the
    // manifest says so, the poses file holds the poses the cloud was fused with, and the eval
    // reports the tails, by band and incidence, for the patches and through the bound planes.
    const fs::path scan = tmp_.path() / "axis";
    const CliRun s = surfgrow(cat({"scan --scene corridor --poses 2 --optical-offset 0 ",
                                   "--pose-error 2mm --pose-error-angle 0.1 -q -o ", q(scan)}));
    ASSERT_EQ(s.code, 0) << s.out;
    const auto manifest = read_json(scan / "scan.json");
    EXPECT_EQ(manifest.at("optical_offset_m").get<double>(), 0.0);
    const auto path = scanner::scan_poses(scanner::corridor_scene().scanner, 2);
    const auto recorded = io::read_poses_file(scan / "poses.txt");
    ASSERT_EQ(recorded.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
        const double moved = (recorded[k].translation() - path[k].translation()).norm();
        EXPECT_GT(moved, 0.0);
        EXPECT_LT(moved, 0.02);  // under 6 sigma per axis
    }
    const fs::path out = tmp_.path() / "axis-out";
    ASSERT_EQ(
        surfgrow(cat({"grow ", q(scan / "cloud.ply"), " -o ", q(out), " --no-picture -q"})).code,
        0);
    const auto surfaces = read_json(out / "surfaces.json");
    EXPECT_EQ(surfaces.at("parameters").at("plane_test"), "disk");
    EXPECT_FALSE(surfaces.at("summary").at("noise_sigma_by_range").at("sigma").empty());
    // Two scans of one corridor: their layers' offsets measured, and larger than the noise within
    // one layer (the range bias, half the datasheet's variance, is not averaged away by eq. (1)).
    const auto& layers = surfaces.at("summary").at("layer_sigma_by_range").at("sigma");
    ASSERT_FALSE(layers.empty());
    EXPECT_GE(layers.at(0).get<double>(),
              surfaces.at("summary").at("noise_sigma_by_range").at("sigma").at(0).get<double>());
    const CliRun e = surfgrow(cat({"eval ", q(out), " --truth ", q(scan),
                                   " --require 'normal_over_45<=0.5%,planes_normal_p95<=2'"}));
    ASSERT_EQ(e.code, 0) << e.out;
    EXPECT_NE(e.out.find("> 45 deg"), std::string::npos) << e.out;
    EXPECT_NE(e.out.find("bound planes"), std::string::npos) << e.out;
    EXPECT_NE(e.out.find("incidence"), std::string::npos) << e.out;
    const auto j = read_json(out / "eval.json");
    EXPECT_FALSE(j.at("incidence").empty());
    EXPECT_FALSE(j.at("through_planes").is_null());
    EXPECT_GT(j.at("through_planes").at("faces_scored").get<int>(), 0);
    // The paper's test is one option away, and a misspelt one is a usage error.
    const CliRun paper =
        surfgrow(cat({"grow ", q(scan / "cloud.ply"), " -o ", q(tmp_.path() / "paper"),
                      " --no-picture -q ", "--plane-test paper --mu-max 24mm"}));
    EXPECT_EQ(paper.code, 0) << paper.out;
    EXPECT_EQ(read_json(tmp_.path() / "paper" / "surfaces.json").at("parameters").at("plane_test"),
              "paper");
    const CliRun bad = surfgrow(
        cat({"grow ", q(scan / "cloud.ply"), " -o ", q(tmp_.path() / "bad"), " --plane-test eq2"}));
    EXPECT_EQ(bad.code, static_cast<int>(ErrorCode::kUsage)) << bad.out;
    EXPECT_NE(bad.out.find("disk or paper"), std::string::npos) << bad.out;
}

TEST_F(CliScan, EvalCatchesATamperedResult) {
    const fs::path out = tmp_.path() / "out";
    ASSERT_EQ(surfgrow(cat({"grow ", q(scan_dir() / "cloud.ply"), " -o ", q(out),
                            " --no-picture --mu-max 48mm"}))
                  .code,
              0);
    // Rotate every normal by 20 degrees about z in surfaces.ply.
    io::StoredResult res = io::read_result_json(out / "surfaces.json");
    ASSERT_FALSE(res.surfaces.empty());
    const double c = std::cos(20 * 3.14159265358979323846 / 180),
                 s = std::sin(20 * 3.14159265358979323846 / 180);
    for (Surface& surf : res.surfaces) {
        const double x = surf.normal.x(), y = surf.normal.y();
        surf.normal.x() = c * x - s * y;
        surf.normal.y() = s * x + c * y;
    }
    std::ostringstream ply;
    io::write_surfaces_ply(ply, res.surfaces, res.meta);
    test::write_bytes(out / "surfaces.ply", ply.str());
    const CliRun e = surfgrow(
        cat({"eval ", q(out), " --truth ", q(scan_dir()), " --require 'normal_median<=3'"}));
    EXPECT_EQ(e.code, kExitRequirementFailed) << e.out;
}

TEST_F(CliScan, EvalRefusesAResultOfAnotherCloud) {
    const fs::path out = tmp_.path() / "out";
    ASSERT_EQ(surfgrow(cat({"scan2cloud ", q(scan_dir() / "scan-000.sgraw"), " -o ",
                            q(tmp_.path() / "one.ply")}))
                  .code,
              0);
    ASSERT_EQ(
        surfgrow(cat({"grow ", q(tmp_.path() / "one.ply"), " -o ", q(out), " --no-picture"})).code,
        0);
    const CliRun e = surfgrow(cat({"eval ", q(out), " --truth ", q(scan_dir())}));
    EXPECT_EQ(e.code, static_cast<int>(ErrorCode::kInvalidParameter)) << e.out;
    EXPECT_NE(e.out.find("not a result of this scan"), std::string::npos) << e.out;
    EXPECT_FALSE(fs::exists(out / "eval.json"));
}

// Every class of bad input: its own exit code, a message naming the problem, no output at all.
struct BadCase {
    std::string name;
    std::function<std::string(const fs::path& dir, const fs::path& scan)> args;
    ErrorCode code;
    std::string expect_in_message;
};

TEST_F(CliScan, BadInputsGiveDistinctCodesAndNoOutput) {
    const fs::path raw = scan_dir() / "scan-000.sgraw";
    const std::vector<BadCase> cases = {
        {"scene file not JSON",
         [](auto& d, auto&) {
             test::write_bytes(d / "bad.json", "{\"format\": \"surfgrow-scene\", ");
             return cat({"scan --scene ", q(d / "bad.json")});
         },
         ErrorCode::kMalformedInput, "bad.json"},
        {"scene with an unknown key",
         [](auto& d, auto&) {
             test::write_bytes(d / "key.json",
                               R"({"format": "surfgrow-scene", "version": 1, "primitives": [)"
                               R"({"type": "box", "min": [0,0,0], "max": [1,1,1], "colour": 3}]})");
             return cat({"scan --scene ", q(d / "key.json")});
         },
         ErrorCode::kMalformedInput, "colour"},
        {"scene with a negative radius",
         [](auto& d, auto&) {
             test::write_bytes(d / "neg.json",
                               R"({"format": "surfgrow-scene", "version": 1, "primitives": [)"
                               R"({"type": "cylinder", "name": "pipe", "base": [0,0,0], )"
                               R"("top": [0,0,1], "radius": -0.1}]})");
             return cat({"scan --scene ", q(d / "neg.json")});
         },
         ErrorCode::kInvalidParameter, "pipe"},
        {"missing scene file",
         [](auto& d, auto&) {
             return cat({"scan --scene ", q(d / "nope.json")});
         },
         ErrorCode::kCannotOpen, "nope.json"},
        {"unknown built-in scene", [](auto&, auto&) { return std::string("scan --scene bridge"); },
         ErrorCode::kInvalidParameter, "ibeam-channel"},
        {"non-rigid pose",
         [](auto& d, auto&) {
             test::write_bytes(d / "scaled.txt", "1.1 0 0 0  0 1 0 0  0 0 1 1  0 0 0 1\n");
             return cat({"scan --scene room-corner --poses ", q(d / "scaled.txt")});
         },
         ErrorCode::kInvalidParameter, "rigid"},
        {"malformed poses file",
         [](auto& d, auto&) {
             test::write_bytes(d / "short.txt", "0 0 1 0 0\n");
             return cat({"scan --scene room-corner --poses ", q(d / "short.txt")});
         },
         ErrorCode::kMalformedInput, "short.txt"},
        {"zero poses",
         [](auto&, auto&) { return std::string("scan --scene room-corner --poses 0"); },
         ErrorCode::kInvalidParameter, "1"},
        {"n <= 2q",
         [](auto&, auto&) { return std::string("scan --scene room-corner --readings 4 --trim 2"); },
         ErrorCode::kInvalidParameter, "n must exceed 2q"},
        {"readings out of range",
         [](auto&, auto&) { return std::string("scan --scene room-corner --readings 300"); },
         ErrorCode::kInvalidParameter, "300"},
        {"unknown laser preset",
         [](auto&, auto&) { return std::string("scan --scene room-corner --laser urg99"); },
         ErrorCode::kInvalidParameter, "urg04lx-paper"},
        {"range beyond the sensor's limits",
         [](auto&, auto&) { return std::string("scan --scene room-corner --max-range 5m"); },
         ErrorCode::kInvalidParameter, "sensor's limits"},
        {"range without unit",
         [](auto&, auto&) { return std::string("scan --scene room-corner --max-range 3"); },
         ErrorCode::kUsage, "unit"},
        {"unknown noise model",
         [](auto&, auto&) { return std::string("scan --scene room-corner --noise soft"); },
         ErrorCode::kUsage, "soft"},
        {"truncated raw scan",
         [](auto& d, auto& scan) {
             const std::string bytes = test::read_bytes(scan / "scan-000.sgraw");
             test::write_bytes(d / "cut.sgraw", bytes.substr(0, bytes.size() - 1000));
             return cat({"scan2cloud ", q(d / "cut.sgraw")});
         },
         ErrorCode::kMalformedInput, "cut.sgraw"},
        {"corrupted raw scan",
         [](auto& d, auto& scan) {
             std::string bytes = test::read_bytes(scan / "scan-000.sgraw");
             bytes[5000] = static_cast<char>(bytes[5000] ^ 0x40);
             test::write_bytes(d / "flip.sgraw", bytes);
             return cat({"scan2cloud ", q(d / "flip.sgraw")});
         },
         ErrorCode::kMalformedInput, "checksum"},
        {"missing raw scan",
         [](auto& d, auto&) {
             return cat({"scan2cloud ", q(d / "none.sgraw")});
         },
         ErrorCode::kCannotOpen, "none.sgraw"},
        {"scan2cloud n <= 2q",
         [](auto&, auto& scan) {
             return cat({"scan2cloud ", q(scan / "scan-000.sgraw"), " --trim 3"});
         },
         ErrorCode::kInvalidParameter, "scan-000.sgraw"},
        {"scan2cloud range beyond the sensor's",
         [](auto&, auto& scan) {
             return cat({"scan2cloud ", q(scan / "scan-000.sgraw"), " --min-range 10mm"});
         },
         ErrorCode::kInvalidParameter, "sensor's limits"},
        {"scan2cloud non-rigid pose",
         [](auto& d, auto& scan) {
             test::write_bytes(d / "shear.txt", "1 0.1 0 0  0 1 0 0  0 0 1 1  0 0 0 1\n");
             return cat(
                 {"scan2cloud ", q(scan / "scan-000.sgraw"), " --poses ", q(d / "shear.txt")});
         },
         ErrorCode::kInvalidParameter, "rigid"},
        {"scan2cloud pose count",
         [](auto&, auto& scan) {
             return cat(
                 {"scan2cloud ", q(scan / "scan-000.sgraw"), " --poses ", q(scan / "poses.txt")});
         },
         ErrorCode::kInvalidParameter, "2 poses for 1 raw scans"},
        {"optical offset without unit",
         [](auto&, auto&) { return std::string("scan --scene room-corner --optical-offset 40"); },
         ErrorCode::kUsage, "unit"},
        {"optical offset of a metre",
         [](auto&, auto&) { return std::string("scan --scene room-corner --optical-offset 1.5m"); },
         ErrorCode::kInvalidParameter, "--optical-offset"},
        {"pose error of a metre",
         [](auto&, auto&) { return std::string("scan --scene room-corner --pose-error 1m"); },
         ErrorCode::kInvalidParameter, "--pose-error"},
        {"negative pose error angle",
         [](auto&, auto&) { return std::string("scan --scene room-corner --pose-error-angle -1"); },
         ErrorCode::kInvalidParameter, "--pose-error-angle"},
        {"eval without truth folder",
         [](auto& d, auto&) {
             return cat({"eval ", q(d / "res"), " --truth ", q(d / "nothing")});
         },
         ErrorCode::kCannotOpen, "nothing"},
    };
    for (const BadCase& c : cases) {
        const fs::path out = tmp_.path() / cat({"out-", std::to_string(&c - cases.data())});
        const std::string args = c.args(tmp_.path(), scan_dir());
        const bool to_file = args.starts_with("scan2cloud");
        const fs::path target = to_file ? out / "cloud.ply" : out;
        if (to_file) fs::create_directories(out);
        const CliRun r = surfgrow(cat({args, args.starts_with("eval") ? "" : " -o ",
                                       args.starts_with("eval") ? "" : q(target)}));
        EXPECT_EQ(r.code, static_cast<int>(c.code)) << c.name << ": " << r.out;
        EXPECT_NE(r.out.find(c.expect_in_message), std::string::npos) << c.name << ": " << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << c.name << ": " << r.out;
        if (to_file)
            EXPECT_TRUE(fs::is_empty(out)) << c.name;
        else
            EXPECT_FALSE(fs::exists(out)) << c.name;
    }
}

TEST(CliDemo, WritesEveryOutputAndPrintsTheSummaryAndEvalLines) {
    test::TempDir dir;
    const CliRun r =
        surfgrow(cat({"demo -o ", q(dir / "demo"), " --require 'registered_workspace>=0.99'"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(" points -> "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("eval: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("range bands"), std::string::npos) << r.out;
    for (const char* f :
         {"surfaces.ply", "surfaces.json", "labels.bin", "run.json", "surfaces.png", "planes.json",
          "coverage.ply", "environment.bt", "eval.json", "scan/cloud.ply", "scan/scene.json",
          "scan/truth-faces.json", "scan/poses.txt", "scan/scan-002.sgraw"})
        EXPECT_TRUE(fs::is_regular_file(dir / "demo" / f)) << f;
    // The demo's result evaluates the same through the files as in memory.
    const auto in_memory = read_json(dir / "demo" / "eval.json");
    const CliRun e =
        surfgrow(cat({"eval ", q(dir / "demo"), " --truth ", q(dir / "demo" / "scan"), " -q"}));
    ASSERT_EQ(e.code, 0) << e.out;
    EXPECT_EQ(read_json(dir / "demo" / "eval.json").at("metrics"), in_memory.at("metrics"));
}

}  // namespace
}  // namespace surfgrow
