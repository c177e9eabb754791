// robot.json parsing (good and bad files), occupancy.ply/json, collision_spheres.json, the
// collision report, and staging into an output folder.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/collision_io.hpp"
#include "surfgrow/io/occupancy_io.hpp"
#include "surfgrow/io/result_outputs.hpp"
#include "surfgrow/io/robot_file.hpp"

namespace surfgrow {
namespace {

using Json = nlohmann::json;

ErrorCode parse_error(const std::string& text, std::string* message = nullptr) {
    try {
        (void)io::parse_robot_json(text, "robot.json", {});
    } catch (const Error& e) {
        if (message) *message = e.what();
        return e.code();
    }
    return ErrorCode::kInternal;  // "no error"
}

TEST(RobotFile, ParsesSpheresAndCapsulesWithUnitsAndOffset) {
    const std::string text = R"({"format": "surfgrow-robot", "units": "mm", "links": [
        {"name": "base", "type": "sphere", "centre": [0, 0, 200], "radius": 150},
        {"name": "arm", "type": "capsule", "a": [0, 0, 300], "b": [400, 0, 300], "radius": 60},
        {"name": "tool", "type": "sphere", "center": [400, 0, 250], "radius": 20},
        {"name": "stub", "type": "capsule", "a": [1, 2, 3], "b": [1, 2, 3], "radius": 5}]})";
    // Into a result in metres whose cloud had an offset of (10, 0, 0).
    const RobotModel r = io::parse_robot_json(text, "robot.json", {1.0, Vec3d(10, 0, 0)});
    ASSERT_EQ(r.links.size(), 4u);
    EXPECT_EQ(r.links[0].name, "base");
    EXPECT_EQ(r.links[0].kind, RobotLink::Kind::kSphere);
    EXPECT_TRUE(r.links[0].shape.a.isApprox(Vec3d(-10, 0, 0.2)));
    EXPECT_EQ(r.links[0].shape.a, r.links[0].shape.b);
    EXPECT_DOUBLE_EQ(r.links[0].shape.radius, 0.15);
    EXPECT_EQ(r.links[1].kind, RobotLink::Kind::kCapsule);
    EXPECT_TRUE(r.links[1].shape.b.isApprox(Vec3d(-9.6, 0, 0.3)));
    EXPECT_DOUBLE_EQ(r.links[1].shape.radius, 0.06);
    EXPECT_TRUE(r.links[2].shape.a.isApprox(Vec3d(-9.6, 0, 0.25)));
    // a == b: a capsule that is a sphere, accepted.
    EXPECT_EQ(r.links[3].shape.a, r.links[3].shape.b);
    // Into a millimetre result: lengths unchanged.
    const RobotModel mm = io::parse_robot_json(text, "robot.json", {0.001, Vec3d::Zero()});
    EXPECT_DOUBLE_EQ(mm.links[1].shape.radius, 60.0);
}

TEST(RobotFile, BadFilesAreMalformedWithAClearMessage) {
    const std::string ok_link =
        R"({"name": "a", "type": "sphere", "centre": [0, 0, 0], "radius": 1})";
    auto robot = [](const std::string& links) {
        return cat({R"({"units": "m", "links": [)", links, "]}"});
    };
    const struct {
        std::string text;
        std::string says;
    } cases[] = {
        {"", "not valid JSON"},
        {"{\"units\": \"m\", \"links\": [", "not valid JSON"},
        {"[1, 2]", "JSON object"},
        {R"({"links": [)" + ok_link + "]}", "units"},
        {R"({"units": "inch", "links": [)" + ok_link + "]}", "unknown units"},
        {R"({"units": "m"})", "links"},
        {R"({"units": "m", "links": []})", "links"},
        {R"({"units": "m", "links": {}})", "links"},
        {R"({"units": "m", "links": [], "extra": 1})", "unknown field"},
        {R"({"format": "urdf", "units": "m", "links": [)" + ok_link + "]}", "format"},
        {robot("3"), "link 0"},
        {robot(R"({"type": "sphere", "centre": [0, 0, 0], "radius": 1})"), "name"},
        {robot(R"({"name": "", "type": "sphere", "centre": [0, 0, 0], "radius": 1})"), "name"},
        {robot(ok_link + "," + ok_link), "earlier link"},
        {robot(R"({"name": "a", "centre": [0, 0, 0], "radius": 1})"), "type"},
        {robot(R"({"name": "a", "type": "box", "centre": [0, 0, 0], "radius": 1})"),
         "unknown type 'box'"},
        {robot(R"({"name": "a", "type": "sphere", "radius": 1})"), "missing \"centre\""},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, 0]})"), "missing \"radius\""},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, 0], "radius": 0})"), "> 0"},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, 0], "radius": -2})"), "> 0"},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, 0], "radius": "1"})"), "number"},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0], "radius": 1})"), "[x, y, z]"},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, "z"], "radius": 1})"), "number"},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, NaN], "radius": 1})"),
         "not valid JSON"},
        {robot(R"({"name": "a", "type": "sphere", "centre": [0, 0, 1e999], "radius": 1})"), ""},
        {robot(
             R"({"name": "a", "type": "sphere", "centre": [0, 0, 0], "center": [0, 0, 0], "radius": 1})"),
         "not both"},
        {robot(
             R"({"name": "a", "type": "sphere", "centre": [0, 0, 0], "radius": 1, "a": [0, 0, 0]})"),
         "unknown field \"a\""},
        {robot(R"({"name": "a", "type": "capsule", "a": [0, 0, 0], "radius": 1})"), "\"b\""},
        {robot(R"({"name": "a", "type": "capsule", "a": [0, 0, 0], "b": [1, 0, 0], "radius": 0})"),
         "> 0"},
        {robot(
             R"({"name": "a", "type": "capsule", "a": [0, 0, 0], "b": [1, 0, 0], "radius": 1, "centre": [0, 0, 0]})"),
         "unknown field"},
    };
    for (const auto& c : cases) {
        std::string message;
        EXPECT_EQ(parse_error(c.text, &message), ErrorCode::kMalformedInput) << c.text;
        EXPECT_NE(message.find("robot.json"), std::string::npos) << message;
        EXPECT_NE(message.find(c.says), std::string::npos) << c.text << "\n -> " << message;
    }
    const test::TempDir dir;
    try {
        (void)io::read_robot_json(dir / "missing.json", {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotOpen);
    }
}

PointCloud box_cloud() {
    PointCloud cloud;
    std::mt19937_64 rng(3);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    return cloud;
}

TEST(OccupancyFiles, PlyHoldsTheCubeCentresAndJsonTheGrid) {
    const PointCloud cloud = box_cloud();
    const GrowerConfig config;
    const GrowResult r = grow_surfaces(cloud, config);
    const OccupancyGrid grid = occupancy_grid(cloud, r, config);
    io::ResultMeta meta;
    meta.input = "box.ply";
    const test::TempDir dir;
    {
        std::ofstream f(dir / "occupancy.ply", std::ios::binary);
        io::write_occupancy_ply(f, grid, meta);
    }
    const PointCloud centres = io::read_cloud(dir / "occupancy.ply");
    ASSERT_EQ(centres.size(), grid.size());
    for (std::size_t k = 0; k < grid.size(); ++k) {
        const Vec3d c = grid.centre(grid.cells()[k]);
        EXPECT_TRUE(centres.points[k].isApprox(c.cast<float>())) << k;
        EXPECT_TRUE(grid.occupied(c));
    }
    std::ostringstream js;
    io::OctomapSummary octo;
    octo.resolution = grid.mu();
    octo.occupied = grid.size();
    io::write_occupancy_json(js, grid, meta, &octo);
    const Json j = Json::parse(js.str());
    EXPECT_EQ(j["format"], "surfgrow-occupancy");
    EXPECT_EQ(j["units"], "m");
    EXPECT_EQ(j["mu"].get<double>(), grid.mu());
    EXPECT_EQ(j["cube_size"].get<double>(), grid.cube_size());
    EXPECT_EQ(j["origin"][0].get<double>(), grid.origin().x());
    EXPECT_EQ(j["occupied_cubes"].get<std::size_t>(), grid.size());
    EXPECT_EQ(j["registered_points"].get<std::uint64_t>(), r.stats.registered);
    EXPECT_EQ(j["octomap"]["file"], "environment.bt");
    EXPECT_EQ(j["octomap"]["carving"], "none");
    // Without an OctoMap: no such section.
    std::ostringstream js2;
    io::write_occupancy_json(js2, grid, meta, nullptr);
    EXPECT_FALSE(Json::parse(js2.str()).contains("octomap"));
}

TEST(OccupancyFiles, OffsetCloudsWriteFileCoordinatesInDouble) {
    PointCloud cloud = box_cloud();
    cloud.offset = Vec3d(500000, 6000000, 30);
    const GrowerConfig config;
    const GrowResult r = grow_surfaces(cloud, config);
    const OccupancyGrid grid = occupancy_grid(cloud, r, config);
    io::ResultMeta meta;
    meta.offset = cloud.offset;
    const test::TempDir dir;
    {
        std::ofstream f(dir / "occupancy.ply", std::ios::binary);
        io::write_occupancy_ply(f, grid, meta);
    }
    const PointCloud centres = io::read_cloud(dir / "occupancy.ply");
    ASSERT_EQ(centres.size(), grid.size());
    const Vec3d first = centres.points[0].cast<double>() + centres.offset;
    EXPECT_TRUE(first.isApprox(grid.centre(grid.cells()[0]) + cloud.offset, 1e-12));
}

TEST(CollisionFiles, SpheresAndReport) {
    std::vector<Surface> surfaces(2);
    surfaces[0].home = {0, 0, 0};
    surfaces[0].radius = 0.012;
    surfaces[1].home = {1, 0, 0};
    surfaces[1].radius = 0.024;
    const CollisionSpheres env = CollisionSpheres::from_surfaces(surfaces);
    io::ResultMeta meta;
    meta.offset = Vec3d(0, 0, 100);
    std::ostringstream s;
    io::write_collision_spheres_json(s, env, meta);
    const Json j = Json::parse(s.str());
    EXPECT_EQ(j["count"], 2);
    EXPECT_EQ(j["spheres_file"], "collision_spheres.ply");
    EXPECT_EQ(j["radius"]["max"], 0.024);
    // The spheres in binary: positions in double here (an offset), the radius in float.
    std::ostringstream ply;
    io::write_collision_spheres_ply(ply, env, meta);
    const std::string bytes = ply.str();
    const std::size_t body = bytes.find("end_header\n") + 11;
    ASSERT_EQ(bytes.size() - body, 2u * (3 * 8 + 4));
    EXPECT_NE(bytes.find("property double x\nproperty double y\nproperty double z\n"
                         "property float radius\n"),
              std::string::npos);
    double centre[3];
    float radius = 0;
    std::memcpy(centre, bytes.data() + body + 28, sizeof centre);
    std::memcpy(&radius, bytes.data() + body + 28 + 24, sizeof radius);
    EXPECT_EQ(Vec3d(centre[0], centre[1], centre[2]), Vec3d(1, 0, 100));
    EXPECT_EQ(radius, 0.024f);
    // Without an offset, float positions: a cloud the generic reader opens.
    std::ostringstream plain;
    io::write_collision_spheres_ply(plain, env, io::ResultMeta{});
    const test::TempDir tmp;
    test::write_bytes(tmp / "spheres.ply", plain.str());
    const PointCloud centres = io::read_cloud(tmp / "spheres.ply");
    ASSERT_EQ(centres.size(), 2u);
    EXPECT_EQ(centres.points[1], Vec3f(1, 0, 0));

    RobotModel robot;
    robot.links.push_back({"base", RobotLink::Kind::kSphere, {{0, 0, 0.5}, {0, 0, 0.5}, 0.1}});
    robot.links.push_back({"arm", RobotLink::Kind::kCapsule, {{0.5, 0, 0.03}, {1, 0, 0.03}, 0.02}});
    const auto results = check_robot(env, robot, 0.005);
    std::ostringstream rep;
    io::write_collision_report_json(rep, env, robot, results, {"robot.json", 0.005}, meta);
    const Json k = Json::parse(rep.str());
    EXPECT_EQ(k["format"], "surfgrow-collision-report");
    EXPECT_EQ(k["collides"], true);
    EXPECT_EQ(k["colliding_links"], 1);
    EXPECT_EQ(k["links"][0]["name"], "base");
    EXPECT_EQ(k["links"][0]["collides"], false);
    EXPECT_NEAR(k["links"][0]["clearance"].get<double>(), 0.388, 1e-12);
    EXPECT_EQ(k["links"][1]["type"], "capsule");
    EXPECT_EQ(k["links"][1]["nearest_surface"], 1);
    EXPECT_EQ(k["links"][1]["nearest_home"], Json::parse("[1, 0, 100]"));
    EXPECT_NEAR(k["min_clearance"].get<double>(), 0.03 - 0.024 - 0.02, 1e-12);

    // An empty environment: nothing near, clearances null.
    const CollisionSpheres none;
    std::ostringstream empty;
    io::write_collision_report_json(empty, none, robot, check_robot(none, robot, 0.0),
                                    {"robot.json", 0.0}, meta);
    const Json e = Json::parse(empty.str());
    EXPECT_TRUE(e["min_clearance"].is_null());
    EXPECT_TRUE(e["links"][0]["clearance"].is_null());
    EXPECT_TRUE(e["links"][0]["nearest_surface"].is_null());
    EXPECT_EQ(e["collides"], false);
    std::ostringstream no_spheres;
    io::write_collision_spheres_json(no_spheres, none, meta);
    EXPECT_EQ(Json::parse(no_spheres.str())["count"], 0);
}

TEST(ResultOutputs, StagesEveryFileOfAPipelineResultTogether) {
    const PointCloud cloud = box_cloud();
    PipelineConfig config;
    config.grow.viewpoint = Vec3d(0, 0, 0);
    const PipelineResult r = run_pipeline(cloud, config);
    ASSERT_TRUE(r.planes && r.coverage && r.occupancy && r.collision);
    const test::TempDir dir;
    io::ResultMeta meta;
    io::OccupancySummary summary;
    {
        io::OutputTransaction tx(dir.path());
        summary = io::stage_result(tx, cloud, config, r, meta);
        tx.commit();
    }
    for (const char* f :
         {"surfaces.ply", "surfaces.json", "labels.bin", "planes.json", "planes.ply",
          "coverage.json", "coverage.ply", "occupancy.ply", "occupancy.json", "environment.bt",
          "collision_spheres.json", "collision_spheres.ply"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / f)) << f;
    for (const char* f : {"surfaces.csv", "planes.obj", "coverage.csv"})
        EXPECT_FALSE(std::filesystem::exists(dir / f)) << f;
    EXPECT_TRUE(summary.octomap_written);
    EXPECT_EQ(summary.octomap.occupied, summary.occupied_cubes);
    EXPECT_GT(summary.octomap.free, 0u);
    EXPECT_EQ(summary.octomap.carving, SensorOrigins::Source::kViewpoint);
    const Json j = Json::parse(test::read_bytes(dir / "occupancy.json"));
    EXPECT_EQ(j["octomap"]["free_leaves"].get<std::uint64_t>(), summary.octomap.free);
    EXPECT_EQ(j["octomap"]["carving"], "viewpoint");
    EXPECT_EQ(Json::parse(test::read_bytes(dir / "collision_spheres.json"))["count"],
              r.grow.surfaces.size());
}

TEST(ResultOutputs, FilesFollowTheChoiceAndTheStagesRun) {
    const PointCloud cloud = box_cloud();
    PipelineConfig config;
    config.grow.viewpoint = Vec3d(0, 0, 0);
    config.coverage.reset();
    config.collision = false;
    const PipelineResult r = run_pipeline(cloud, config);
    EXPECT_TRUE(r.planes && r.occupancy);
    EXPECT_FALSE(r.coverage || r.collision);
    const test::TempDir dir;
    io::ResultFiles files;
    files.labels = false;
    files.csv = true;
    files.planes_obj = true;
    files.octomap = false;
    {
        io::OutputTransaction tx(dir.path());
        const io::OccupancySummary s = io::stage_result(tx, cloud, config, r, {}, files);
        EXPECT_FALSE(s.octomap_written);
        tx.commit();
    }
    for (const char* f : {"surfaces.ply", "surfaces.json", "surfaces.csv", "planes.json",
                          "planes.ply", "planes.obj", "occupancy.ply", "occupancy.json"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / f)) << f;
    for (const char* f : {"labels.bin", "labels.txt", "coverage.json", "coverage.ply",
                          "environment.bt", "collision_spheres.json", "collision_spheres.ply"})
        EXPECT_FALSE(std::filesystem::exists(dir / f)) << f;
}

}  // namespace
}  // namespace surfgrow
