// End-to-end tests of `surfgrow grow`: the real binary on real files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

// Runs the CLI with arguments (already shell-quoted where needed).
CliRun surfgrow(const std::string& args) {
    return test::run_surfgrow(args);
}

std::string q(const fs::path& p) {
    return test::quoted(p);
}

// A box scanned on a 5 mm grid with noise, written as a binary PLY; a few NaN points mixed in.
PointCloud box_cloud(double scale = 1.0) {
    PointCloud cloud;
    std::mt19937_64 rng(3);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    for (auto& p : cloud.points) p *= static_cast<float>(scale);
    for (std::size_t i = 5; i < cloud.size(); i += 997)
        cloud.points[i] = Vec3f::Constant(std::nanf(""));
    return cloud;
}

class CliGrow : public ::testing::Test {
  protected:
    void SetUp() override {
        cloud_ = box_cloud();
        input_ = dir_ / "box.ply";
        io::write_cloud(input_, cloud_);
    }
    test::TempDir dir_;
    PointCloud cloud_;
    fs::path input_;
};

TEST_F(CliGrow, WritesEveryOutputAndTheSummaryLine) {
    const CliRun r = surfgrow("grow " + q(input_) + " -o " + q(dir_ / "out") + " --csv");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(std::to_string(cloud_.size()) + " points -> "), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("% registered"), std::string::npos) << r.out;
    for (const char* f :
         {"surfaces.ply", "surfaces.json", "surfaces.csv", "labels.txt", "run.json", "surfaces.png",
          "planes.json", "planes.ply", "coverage.json", "coverage.csv", "occupancy.ply",
          "occupancy.json", "environment.bt", "collision_spheres.json"})
        EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / f)) << f;
    // Labels: one per input point, NaN points unregistered, ids within range.
    const auto labels = io::read_labels_txt(dir_ / "out" / "labels.txt");
    ASSERT_EQ(labels.size(), cloud_.size());
    const io::StoredResult res = io::read_result_json(dir_ / "out" / "surfaces.json");
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (!is_finite(cloud_.points[i])) {
            EXPECT_EQ(labels[i], -1);
        }
        EXPECT_LT(labels[i], static_cast<std::int32_t>(res.surfaces.size()));
    }
    EXPECT_GE(double(res.stats.registered) / double(res.stats.valid_points), 0.99);
    // surfaces.ply opens as a cloud with one point per surface.
    const PointCloud surf = io::read_cloud(dir_ / "out" / "surfaces.ply");
    EXPECT_EQ(surf.size(), res.surfaces.size());
    // run.json carries the timings; surfaces.json does not.
    const auto run = nlohmann::json::parse(test::read_bytes(dir_ / "out" / "run.json"));
    EXPECT_TRUE(run["seconds"].contains("grow"));
}

TEST_F(CliGrow, ByteIdenticalOutputsForAnyThreadCount) {
    // 100000: more than any machine can use, clamped with a note (it crashed once).
    for (int t : {1, 2, 4, 100000}) {
        const CliRun r =
            surfgrow("grow " + q(input_) + " -o " + q(dir_ / cat({"t", std::to_string(t)})) +
                     " --seed 9 --threads " + std::to_string(t));
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_EQ(r.out.find("more than this machine can use") != std::string::npos, t == 100000)
            << r.out;
    }
    for (const char* f :
         {"surfaces.ply", "surfaces.json", "labels.txt", "surfaces.png", "planes.json",
          "planes.ply", "coverage.json", "coverage.csv", "occupancy.ply", "occupancy.json",
          "environment.bt", "collision_spheres.json"}) {
        const std::string ref = test::read_bytes(dir_ / "t1" / f);
        EXPECT_EQ(test::read_bytes(dir_ / "t2" / f), ref) << f;
        EXPECT_EQ(test::read_bytes(dir_ / "t4" / f), ref) << f;
        EXPECT_EQ(test::read_bytes(dir_ / "t100000" / f), ref) << f;
    }
}

// The robot outputs grow writes are the ones their subcommands make from the stored result.
TEST_F(CliGrow, RobotOutputsMatchTheirSubcommands) {
    const fs::path out = dir_ / "out", sub = dir_ / "sub";
    ASSERT_EQ(surfgrow(cat({"grow ", q(input_), " -o ", q(out), " --seed 4 -q"})).code, 0);
    ASSERT_EQ(surfgrow(cat({"grow ", q(input_), " -o ", q(sub),
                            " --seed 4 -q --no-planes --no-occupancy --no-octomap --no-collision"}))
                  .code,
              0);
    for (const char* f : {"planes.json", "coverage.json", "occupancy.json", "environment.bt",
                          "collision_spheres.json"})
        EXPECT_FALSE(fs::exists(sub / f)) << f;
    const std::string c = cat({" --cloud ", q(input_), " -q"});
    ASSERT_EQ(surfgrow(cat({"planes ", q(sub), c})).code, 0);
    ASSERT_EQ(surfgrow(cat({"coverage ", q(sub), " -q"})).code, 0);
    ASSERT_EQ(surfgrow(cat({"occupancy ", q(sub), c})).code, 0);
    for (const char* f : {"planes.json", "planes.ply", "coverage.json", "coverage.csv",
                          "occupancy.ply", "occupancy.json", "environment.bt"})
        EXPECT_EQ(test::read_bytes(sub / f), test::read_bytes(out / f)) << f;
    // --stats reports each robot output; --no-coverage keeps the planes.
    const CliRun r = surfgrow(cat({"grow ", q(input_), " -o ", q(dir_ / "nc"),
                                   " --seed 4 --stats --no-coverage --no-picture"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(" planes, "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("occupied cubes"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(dir_ / "nc" / "planes.json"));
    EXPECT_FALSE(fs::exists(dir_ / "nc" / "coverage.json"));
    // A bad robot-output parameter is refused before anything is written.
    const CliRun bad =
        surfgrow(cat({"grow ", q(input_), " -o ", q(dir_ / "bad"), " --angle-band 40:5"}));
    EXPECT_EQ(bad.code, static_cast<int>(ErrorCode::kInvalidParameter)) << bad.out;
    EXPECT_FALSE(fs::exists(dir_ / "bad" / "surfaces.json"));
}

TEST_F(CliGrow, MillimetreCloudsGiveTheSameSurfaces) {
    io::write_cloud(dir_ / "box_mm.ply", box_cloud(1000.0));
    ASSERT_EQ(surfgrow("grow " + q(input_) + " -o " + q(dir_ / "m") + " --no-picture").code, 0);
    const CliRun r = surfgrow("grow " + q(dir_ / "box_mm.ply") + " -o " + q(dir_ / "mm") +
                              " --units mm --mu 1.2cm --no-picture");
    ASSERT_EQ(r.code, 0) << r.out;
    const io::StoredResult m = io::read_result_json(dir_ / "m" / "surfaces.json");
    const io::StoredResult mm = io::read_result_json(dir_ / "mm" / "surfaces.json");
    EXPECT_EQ(mm.meta.units, "mm");
    EXPECT_DOUBLE_EQ(mm.config.mu, 12.0);
    ASSERT_EQ(m.surfaces.size(), mm.surfaces.size());
    EXPECT_EQ(m.stats.registered, mm.stats.registered);
}

// Every class of bad input: its own exit code, one clear line naming the problem, no output.
struct BadCase {
    std::string name;
    std::function<std::string(const fs::path& dir, const fs::path& good)> args;
    ErrorCode code;
    std::string expect_in_message;
};

TEST_F(CliGrow, BadInputsGiveDistinctCodesAndNoOutput) {
    const std::vector<BadCase> cases = {
        {"missing file", [](auto& d, auto&) { return q(d / "nope.ply"); }, ErrorCode::kCannotOpen,
         "nope.ply"},
        {"folder as input", [](auto& d, auto&) { return q(d); }, ErrorCode::kCannotOpen, ""},
        {"unknown format",
         [](auto& d, auto&) {
             test::write_bytes(d / "cloud.bin", std::string("\x01\x02\x03garbage\x00\xff", 12));
             return q(d / "cloud.bin");
         },
         ErrorCode::kUnknownFormat, "cloud.bin"},
        {"truncated ply",
         [](auto& d, auto& good) {
             const std::string bytes = test::read_bytes(good);
             test::write_bytes(d / "cut.ply", bytes.substr(0, bytes.size() / 2));
             return q(d / "cut.ply");
         },
         ErrorCode::kMalformedInput, "cut.ply"},
        {"bad header",
         [](auto& d, auto&) {
             test::write_bytes(d / "bad.pcd",
                               "VERSION .7\nFIELDS x y z\nSIZE 4 4\nTYPE F F F\nDATA ascii\n");
             return q(d / "bad.pcd");
         },
         ErrorCode::kMalformedInput, "bad.pcd"},
        {"mu zero", [](auto&, auto& good) { return q(good) + " --mu 0mm"; },
         ErrorCode::kInvalidParameter, "mu"},
        {"mu negative", [](auto&, auto& good) { return q(good) + " --mu -5mm"; },
         ErrorCode::kInvalidParameter, "mu"},
        {"mu beyond the cloud", [](auto&, auto& good) { return q(good) + " --mu 1e40m"; },
         ErrorCode::kInvalidParameter, "larger than the whole cloud"},
        {"mu without unit", [](auto&, auto& good) { return q(good) + " --mu 12"; },
         ErrorCode::kUsage, "unit"},
        {"min-pts too small", [](auto&, auto& good) { return q(good) + " --min-pts 2"; },
         ErrorCode::kInvalidParameter, "min-pts"},
        {"alpha at most one", [](auto&, auto& good) { return q(good) + " --alpha 1"; },
         ErrorCode::kInvalidParameter, "alpha"},
        {"unknown plane test", [](auto&, auto& good) { return q(good) + " --plane-test eq2"; },
         ErrorCode::kUsage, "disk or paper"},
        {"spread above a disk's", [](auto&, auto& good) { return q(good) + " --min-spread 2"; },
         ErrorCode::kInvalidParameter, "min-spread"},
        {"incidence of 0 degrees", [](auto&, auto& good) { return q(good) + " --max-incidence 0"; },
         ErrorCode::kInvalidParameter, "max-incidence"},
        {"tolerance under one sigma",
         [](auto&, auto& good) { return q(good) + " --noise-sigmas 0.5"; },
         ErrorCode::kInvalidParameter, "noise-sigmas"},
        {"unknown option", [](auto&, auto& good) { return q(good) + " --frobnicate"; },
         ErrorCode::kUsage, ""},
        {"bad units", [](auto&, auto& good) { return q(good) + " --units furlong"; },
         ErrorCode::kUsage, "furlong"},
        {"absurd extent",
         [](auto& d, auto&) {
             PointCloud c;
             c.points = {{-1e30f, 0, 0}, {1e30f, 1, 1}, {0, 0, 0}};
             io::write_cloud(d / "huge.ply", c);
             return q(d / "huge.ply");
         },
         ErrorCode::kCloudTooLarge, "crop"},
    };
    for (const BadCase& c : cases) {
        const fs::path out = dir_ / cat({"out-", std::to_string(&c - cases.data())});
        const CliRun r = surfgrow("grow " + c.args(dir_.path(), input_) + " -o " + q(out));
        EXPECT_EQ(r.code, static_cast<int>(c.code)) << c.name << ": " << r.out;
        EXPECT_NE(r.out.find(c.expect_in_message), std::string::npos) << c.name << ": " << r.out;
        EXPECT_FALSE(fs::exists(out / "surfaces.json")) << c.name;
    }
}

TEST_F(CliGrow, AFailedRunNeverTouchesAGoodOutput) {
    ASSERT_EQ(surfgrow("grow " + q(input_) + " -o " + q(dir_ / "out") + " --no-picture").code, 0);
    const std::string before = test::read_bytes(dir_ / "out" / "surfaces.json");
    const std::string bytes = test::read_bytes(input_);
    test::write_bytes(dir_ / "cut.ply", bytes.substr(0, bytes.size() - 100));
    EXPECT_EQ(surfgrow("grow " + q(dir_ / "cut.ply") + " -o " + q(dir_ / "out")).code,
              static_cast<int>(ErrorCode::kMalformedInput));
    EXPECT_EQ(test::read_bytes(dir_ / "out" / "surfaces.json"), before);
    for (const auto& e : fs::directory_iterator(dir_ / "out"))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(CliGrow, EmptyCloudIsNotAnError) {
    test::write_bytes(
        dir_ / "empty.ply",
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n");
    const CliRun r = surfgrow("grow " + q(dir_ / "empty.ply") + " -o " + q(dir_ / "out"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("0 points -> 0 surfaces"), std::string::npos) << r.out;
    EXPECT_TRUE(test::read_bytes(dir_ / "out" / "labels.txt").empty());
}

TEST_F(CliGrow, UnwritableOutputIsCannotWrite) {
    test::write_bytes(dir_ / "a_file", "x");
    const CliRun r = surfgrow("grow " + q(input_) + " -o " + q(dir_ / "a_file"));
    EXPECT_EQ(r.code, static_cast<int>(ErrorCode::kCannotWrite)) << r.out;
    EXPECT_NE(r.out.find("a_file"), std::string::npos) << r.out;
}

TEST(Cli, VersionAndHelp) {
    EXPECT_EQ(surfgrow("--version").code, 0);
    const CliRun help = surfgrow("grow --help");
    EXPECT_EQ(help.code, 0);
    EXPECT_NE(help.out.find("--mu"), std::string::npos);
    EXPECT_EQ(surfgrow("").code, static_cast<int>(ErrorCode::kUsage));
}

}  // namespace
}  // namespace surfgrow
