// End-to-end tests of `surfgrow occupancy` and `surfgrow collide`: the real binary on real files.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
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
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"

namespace surfgrow {
namespace {

// The exit status of `collide --fail-on-collision` on a collision (README, "When something is
// wrong").
constexpr int kExitCollision = 10;

namespace fs = std::filesystem;
using Json = nlohmann::json;

using test::CliRun;

// Runs the CLI with arguments (already shell-quoted where needed).
CliRun surfgrow(const std::string& args) {
    return test::run_surfgrow(args);
}

std::string q(const fs::path& p) {
    return test::quoted(p);
}

int code(ErrorCode c) {
    return static_cast<int>(c);
}

PointCloud box_cloud() {
    PointCloud cloud;
    std::mt19937_64 rng(3);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    for (std::size_t i = 5; i < cloud.size(); i += 997)
        cloud.points[i] = Vec3f::Constant(std::nanf(""));
    return cloud;
}

std::size_t occupied_leaves(const fs::path& bt, std::size_t* free = nullptr) {
    octomap::OcTree tree(0.1);
    EXPECT_TRUE(tree.readBinary(bt.string()));
    std::size_t occ = 0, fr = 0;
    const unsigned depth = tree.getTreeDepth();
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        const std::size_t n = std::size_t{1} << (3 * (depth - it.getDepth()));
        (tree.isNodeOccupied(*it) ? occ : fr) += n;
    }
    if (free) *free = fr;
    return occ;
}

class CliRobot : public ::testing::Test {
  protected:
    void SetUp() override {
        cloud_ = box_cloud();
        input_ = dir_ / "box.ply";
        io::write_cloud(input_, cloud_);
        out_ = dir_ / "out";
        const CliRun r = surfgrow(cat({"grow ", q(input_), " -o ", q(out_), " --no-picture"}));
        ASSERT_EQ(r.code, 0) << r.out;
    }
    void write(const fs::path& p, const std::string& text) { test::write_bytes(p, text); }
    test::TempDir dir_;
    PointCloud cloud_;
    fs::path input_, out_;
};

TEST_F(CliRobot, OccupancyWritesTheGridAndAnOctomapThatLoads) {
    const CliRun r = surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(input_)}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("occupied cubes of 12 mm"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("without free space"), std::string::npos) << r.out;
    // The same grid as computed in process from the stored labels.
    const auto labels = io::read_labels(out_ / "labels.bin");
    const OccupancyGrid grid = occupancy_grid(io::read_cloud(input_), labels, GrowerConfig{});
    const Json j = Json::parse(test::read_bytes(out_ / "occupancy.json"));
    EXPECT_EQ(j["occupied_cubes"].get<std::size_t>(), grid.size());
    EXPECT_EQ(j["cube_size"].get<double>(), grid.cube_size());
    EXPECT_EQ(j["origin"][2].get<double>(), grid.origin().z());
    EXPECT_EQ(io::read_cloud(out_ / "occupancy.ply").size(), grid.size());
    std::size_t free = 1;
    EXPECT_EQ(occupied_leaves(out_ / "environment.bt", &free), grid.size());
    EXPECT_EQ(free, 0u);
    // Same bytes again (deterministic), and the surfaces are untouched.
    const std::string bt = test::read_bytes(out_ / "environment.bt");
    const std::string surfaces = test::read_bytes(out_ / "surfaces.json");
    ASSERT_EQ(surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(input_), " --threads 1"})).code,
              0);
    EXPECT_EQ(test::read_bytes(out_ / "environment.bt"), bt);
    EXPECT_EQ(test::read_bytes(out_ / "surfaces.json"), surfaces);
}

TEST_F(CliRobot, OccupancyCarvesFreeSpaceFromAViewpoint) {
    const CliRun r =
        surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(input_), " --viewpoint 0,0,0m"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("(viewpoint)"), std::string::npos) << r.out;
    std::size_t free = 0;
    const std::size_t occ = occupied_leaves(out_ / "environment.bt", &free);
    EXPECT_GT(free, occ);
    const Json j = Json::parse(test::read_bytes(out_ / "occupancy.json"));
    EXPECT_EQ(j["octomap"]["carving"], "viewpoint");
    EXPECT_EQ(j["octomap"]["free_leaves"].get<std::size_t>(), free);
    // --no-octomap: no .bt written this time, the others are.
    fs::remove(out_ / "environment.bt");
    ASSERT_EQ(
        surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(input_), " --no-octomap -q"})).code, 0);
    EXPECT_FALSE(fs::exists(out_ / "environment.bt"));
    EXPECT_FALSE(Json::parse(test::read_bytes(out_ / "occupancy.json")).contains("octomap"));
}

TEST_F(CliRobot, OccupancyFollowsTheCropOfTheResult) {
    const fs::path crop = dir_ / "crop";
    ASSERT_EQ(surfgrow(cat({"grow ", q(input_), " -o ", q(crop),
                            " --no-picture --crop-radius 25cm --crop-center 0.1,0,0.55m"}))
                  .code,
              0);
    const CliRun r = surfgrow(cat({"occupancy ", q(crop), " --cloud ", q(input_)}));
    ASSERT_EQ(r.code, 0) << r.out;
    GrowerConfig config;
    config.crop.radius = 0.25;
    config.crop.center = Vec3d(0.1, 0, 0.55);
    const OccupancyGrid grid =
        occupancy_grid(io::read_cloud(input_), io::read_labels(crop / "labels.bin"), config);
    const Json j = Json::parse(test::read_bytes(crop / "occupancy.json"));
    EXPECT_EQ(j["occupied_cubes"].get<std::size_t>(), grid.size());
    EXPECT_EQ(j["origin"][0].get<double>(), grid.origin().x());
}

TEST_F(CliRobot, OccupancyRefusesAnotherCloudAndMissingInputs) {
    PointCloud other = cloud_;
    other.points.resize(other.size() / 2);
    io::write_cloud(dir_ / "other.ply", other);
    CliRun r = surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(dir_ / "other.ply")}));
    EXPECT_EQ(r.code, code(ErrorCode::kMalformedInput)) << r.out;
    EXPECT_NE(r.out.find("labels.bin"), std::string::npos) << r.out;
    // Same size, different points: the grown-point count gives it away.
    PointCloud moved = cloud_;
    for (std::size_t i = 0; i < moved.size(); i += 3) moved.points[i] = Vec3f::Constant(NAN);
    io::write_cloud(dir_ / "moved.ply", moved);
    r = surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(dir_ / "moved.ply")}));
    EXPECT_EQ(r.code, code(ErrorCode::kMalformedInput)) << r.out;
    EXPECT_NE(r.out.find("points to grow"), std::string::npos) << r.out;
    r = surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(dir_ / "missing.ply")}));
    EXPECT_EQ(r.code, code(ErrorCode::kCannotOpen)) << r.out;
    r = surfgrow(cat({"occupancy ", q(dir_ / "nothing"), " --cloud ", q(input_)}));
    EXPECT_EQ(r.code, code(ErrorCode::kCannotOpen)) << r.out;
    r = surfgrow(cat({"occupancy ", q(out_)}));
    EXPECT_EQ(r.code, code(ErrorCode::kUsage)) << r.out;
    r = surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(input_), " --viewpoint 0,0,1"}));
    EXPECT_EQ(r.code, code(ErrorCode::kUsage)) << r.out;
    fs::remove(out_ / "labels.bin");
    r = surfgrow(cat({"occupancy ", q(out_), " --cloud ", q(input_)}));
    EXPECT_EQ(r.code, code(ErrorCode::kCannotOpen)) << r.out;
}

constexpr const char* kRobot = R"({"units": "mm", "links": [
    {"name": "base", "type": "sphere", "centre": [0, 0, 1000], "radius": 100},
    {"name": "upper_arm", "type": "capsule", "a": [0, 0, 1000], "b": [0, 0, 800], "radius": 50},
    {"name": "tool", "type": "sphere", "centre": [0, 0, 725], "radius": 20}]})";

TEST_F(CliRobot, CollideReportsEachLinkAgainstBruteForce) {
    write(dir_ / "robot.json", kRobot);
    const CliRun r = surfgrow(
        cat({"collide ", q(out_), " --robot ", q(dir_ / "robot.json"), " --tolerance 5mm"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("base"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("links collide (tolerance 5 mm"), std::string::npos) << r.out;
    const Json rep = Json::parse(test::read_bytes(out_ / "collision.json"));
    const io::StoredResult res = io::read_result_json(out_ / "surfaces.json");
    ASSERT_EQ(rep["links"].size(), 3u);
    EXPECT_EQ(rep["environment_spheres"].get<std::size_t>(), res.surfaces.size());
    // Brute force over every surface's sphere.
    const Capsule links[] = {{{0, 0, 1}, {0, 0, 1}, 0.1},
                             {{0, 0, 1}, {0, 0, 0.8}, 0.05},
                             {{0, 0, 0.725}, {0, 0, 0.725}, 0.02}};
    bool any = false;
    for (int k = 0; k < 3; ++k) {
        double best = INFINITY;
        for (const Surface& s : res.surfaces)
            best = std::min(best, clearance(Sphere{s.home, s.radius}, links[k]));
        const Json& l = rep["links"][static_cast<std::size_t>(k)];
        EXPECT_NEAR(l["clearance"].get<double>(), best, 1e-9) << k;
        EXPECT_EQ(l["collides"].get<bool>(), best < 0.005) << k;
        any = any || best < 0.005;
    }
    EXPECT_TRUE(any);  // the tool reaches the box's top (z = 0.7)
    EXPECT_EQ(rep["collides"], true);
    EXPECT_NE(r.out.find("COLLIDES"), std::string::npos) << r.out;
    // --fail-on-collision: exit 10, report still written.
    fs::remove(out_ / "collision.json");
    const CliRun f = surfgrow(cat({"collide ", q(out_), " --robot ", q(dir_ / "robot.json"),
                                   " --fail-on-collision -q --report ", q(dir_ / "rep.json")}));
    EXPECT_EQ(f.code, kExitCollision) << f.out;
    EXPECT_TRUE(fs::exists(dir_ / "rep.json"));
    EXPECT_FALSE(fs::exists(out_ / "collision.json"));
}

TEST_F(CliRobot, CollideClearRobotExitsZeroEvenWithFailOnCollision) {
    write(dir_ / "far.json", R"({"units": "m", "links": [
        {"name": "far", "type": "capsule", "a": [2, 2, 2], "b": [3, 2, 2], "radius": 0.1}]})");
    const CliRun r = surfgrow(cat({"collide ", q(out_), " --robot ", q(dir_ / "far.json"),
                                   " --tolerance 1cm --fail-on-collision"}));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("0 of 1 links collide"), std::string::npos) << r.out;
    EXPECT_EQ(Json::parse(test::read_bytes(out_ / "collision.json"))["collides"], false);
}

TEST_F(CliRobot, CollideBadRobotFilesAndOptions) {
    const fs::path robot = dir_ / "robot.json";
    const struct {
        const char* text;
        int code;
    } cases[] = {
        {"not json", code(ErrorCode::kMalformedInput)},
        {R"({"links": [{"name": "a", "type": "sphere", "centre": [0,0,0], "radius": 1}]})",
         code(ErrorCode::kMalformedInput)},
        {R"({"units": "m", "links": [{"name": "a", "type": "sphere", "centre": [0,0,0], "radius": -1}]})",
         code(ErrorCode::kMalformedInput)},
        {R"({"units": "m", "links": [{"name": "a", "type": "sphere", "centre": [0,0,0], "radius": 0}]})",
         code(ErrorCode::kMalformedInput)},
        {R"({"units": "m", "links": [{"name": "a", "type": "cone", "centre": [0,0,0], "radius": 1}]})",
         code(ErrorCode::kMalformedInput)},
        {R"({"units": "m", "links": [{"name": "a", "type": "capsule", "a": [0,0,0], "radius": 1}]})",
         code(ErrorCode::kMalformedInput)},
        {R"({"units": "m", "links": []})", code(ErrorCode::kMalformedInput)},
    };
    for (const auto& c : cases) {
        write(robot, c.text);
        const CliRun r = surfgrow(cat({"collide ", q(out_), " --robot ", q(robot)}));
        EXPECT_EQ(r.code, c.code) << c.text << "\n" << r.out;
        EXPECT_NE(r.out.find("robot.json"), std::string::npos) << r.out;
    }
    write(robot, kRobot);
    EXPECT_EQ(surfgrow(cat({"collide ", q(out_), " --robot ", q(dir_ / "none.json")})).code,
              code(ErrorCode::kCannotOpen));
    EXPECT_EQ(surfgrow(cat({"collide ", q(out_)})).code, code(ErrorCode::kUsage));
    EXPECT_EQ(surfgrow(cat({"collide ", q(out_), " --robot ", q(robot), " --tolerance 5"})).code,
              code(ErrorCode::kUsage));
    EXPECT_EQ(surfgrow(cat({"collide ", q(out_), " --robot ", q(robot), " --tolerance -5mm"})).code,
              code(ErrorCode::kInvalidParameter));
    EXPECT_EQ(surfgrow(cat({"collide ", q(dir_ / "nothing"), " --robot ", q(robot)})).code,
              code(ErrorCode::kCannotOpen));
}

TEST_F(CliRobot, EmptyResultsAreSuccessesWithNothingInThem) {
    PointCloud nan_cloud;
    nan_cloud.points.assign(10, Vec3f::Constant(std::nanf("")));
    io::write_cloud(dir_ / "nan.ply", nan_cloud);
    const fs::path empty = dir_ / "empty";
    ASSERT_EQ(surfgrow(cat({"grow ", q(dir_ / "nan.ply"), " -o ", q(empty), " --no-picture"})).code,
              0);
    CliRun r = surfgrow(
        cat({"occupancy ", q(empty), " --cloud ", q(dir_ / "nan.ply"), " --viewpoint 0,0,0m"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("0 occupied cubes"), std::string::npos) << r.out;
    EXPECT_EQ(occupied_leaves(empty / "environment.bt"), 0u);
    EXPECT_EQ(io::read_cloud(empty / "occupancy.ply").size(), 0u);
    write(dir_ / "robot.json", kRobot);
    r = surfgrow(
        cat({"collide ", q(empty), " --robot ", q(dir_ / "robot.json"), " --fail-on-collision"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("clearance none"), std::string::npos) << r.out;
    const Json rep = Json::parse(test::read_bytes(empty / "collision.json"));
    EXPECT_TRUE(rep["min_clearance"].is_null());
    EXPECT_EQ(rep["environment_spheres"], 0);
}

}  // namespace
}  // namespace surfgrow
