// End-to-end tests of `surfgrow planes` and `surfgrow coverage`: the real binary on real files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"

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

// An L of a floor with a square hole and a wall, 5 mm grid, 1 mm noise; scale 1000 for mm.
PointCloud l_cloud(double scale = 1.0) {
    PointCloud cloud;
    std::mt19937_64 rng(11);
    std::vector<Vec3f> pts;
    test::sample_rect({{0.2, 0.15, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15}, 0.005, 0.3,
                      0.001, rng, pts);
    test::sample_rect({{0, 0.15, 0.15}, Vec3d::UnitY(), Vec3d::UnitZ(), 0.15, 0.15}, 0.005, 0.3,
                      0.001, rng, pts);
    for (const Vec3f& p : pts)
        if (!(p.z() < 0.01f && std::abs(p.x() - 0.25f) < 0.04f && std::abs(p.y() - 0.15f) < 0.04f))
            cloud.points.push_back(p * static_cast<float>(scale));
    return cloud;
}

class CliPlanes : public ::testing::Test {
  protected:
    void SetUp() override {
        cloud_ = dir_ / "l.ply";
        io::write_cloud(cloud_, l_cloud());
        out_ = dir_ / "out";
        const CliRun r = surfgrow(cat({"grow ", q(cloud_), " -o ", q(out_),
                                       " --no-picture --no-planes --viewpoint 0.3,0.4,0.5m -q"}));
        ASSERT_EQ(r.code, 0) << r.out;
    }
    test::TempDir dir_;
    fs::path cloud_, out_;
};

TEST_F(CliPlanes, PlanesThenCoverageWriteEveryOutput) {
    CliRun r = surfgrow(cat({"planes ", q(out_), " --cloud ", q(cloud_), " --obj"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(" surfaces -> "), std::string::npos) << r.out;
    for (const char* f : {"planes.json", "planes.ply", "planes.obj"})
        EXPECT_TRUE(fs::is_regular_file(out_ / f)) << f;
    const io::StoredPlanes planes = io::read_planes_json(out_ / "planes.json");
    ASSERT_GE(planes.planes.planes.size(), 2u);
    EXPECT_LT(angle_between(planes.planes.planes[0].normal, Vec3d::UnitZ()), 0.01);
    EXPECT_EQ(planes.planes.planes[0].polygons.at(0).holes.size(), 1u);  // the floor's hole
    EXPECT_EQ(planes.planes.config.mu, 0.012);
    const PlaneMesh mesh = io::read_planes_ply(out_ / "planes.ply");
    EXPECT_FALSE(mesh.triangles.empty());

    r = surfgrow(cat({"coverage ", q(out_), " --coverage-csv"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(" goals on "), std::string::npos) << r.out;
    const io::StoredCoverage cov = io::read_coverage_json(out_ / "coverage.json");
    EXPECT_GE(cov.plan.stats.coverage, 0.99);
    EXPECT_EQ(cov.plan.config.blast_radius, 0.012);
    EXPECT_EQ(cov.plan.config.standoff, 0.3);
    const auto rows = io::read_coverage_csv(out_ / "coverage.csv");
    ASSERT_EQ(rows.size(), cov.plan.goals.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const CoverageGoal& g = rows[k];
        const double a = angle_between(-g.tool_axis, g.normal) * 180 / M_PI;
        ASSERT_GE(a, 5 - 1e-6);
        ASSERT_LE(a, 40 + 1e-6);
        // The text and the binary goals (coverage.ply, floats) are the same plan.
        ASSERT_LT((g.position - cov.plan.goals[k].position).norm(), 1e-6) << k;
        ASSERT_EQ(g.plane, cov.plan.goals[k].plane) << k;
    }
    // Without --coverage-csv the text form of an earlier run does not survive.
    ASSERT_EQ(surfgrow(cat({"coverage ", q(out_), " -q"})).code, 0);
    EXPECT_FALSE(fs::exists(out_ / "coverage.csv"));
}

// The picture grow drew is coloured by plane: planes with other settings draws it again, the
// picture `render` draws of the folder now, not the old planes' colours.
TEST_F(CliPlanes, NewPlanesRedrawThePicture) {
    const fs::path out = dir_ / "pictured";
    CliRun r = surfgrow(cat({"grow ", q(cloud_), " -o ", q(out), " --viewpoint 0.3,0.4,0.5m -q"}));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string before = test::read_bytes(out / "surfaces.png");
    // Nearly every patch its own plane: other colours.
    r = surfgrow(cat({"planes ", q(out), " --cloud ", q(cloud_),
                      " --angle 0.5 --offset 0.05mm "
                      "--no-gap-bridging -q"}));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string after = test::read_bytes(out / "surfaces.png");
    EXPECT_NE(after, before);
    const fs::path drawn = dir_ / "drawn.png";
    r = surfgrow(cat({"render ", q(out), " -o ", q(drawn)}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(test::read_bytes(drawn), after);
    EXPECT_FALSE(fs::exists(out / "corner.png"));  // grow drew none: planes draws none
}

TEST_F(CliPlanes, CoverageOptionsCarryUnitsAndReachThePlan) {
    ASSERT_EQ(surfgrow(cat({"planes ", q(out_), " --cloud ", q(cloud_), " -q"})).code, 0);
    const CliRun r =
        surfgrow(cat({"coverage ", q(out_), " --blast-radius 2.4cm --standoff 0.5m ",
                      "--angle-band 10:30 --tilt 20 --start 0,0,1m --spacing 6mm -q"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(r.out.empty()) << r.out;
    const io::StoredCoverage cov = io::read_coverage_json(out_ / "coverage.json");
    EXPECT_DOUBLE_EQ(cov.plan.config.blast_radius, 0.024);
    EXPECT_DOUBLE_EQ(cov.plan.config.standoff, 0.5);
    EXPECT_DOUBLE_EQ(cov.plan.config.sample_spacing, 0.006);
    ASSERT_TRUE(cov.plan.config.start.has_value());
    EXPECT_EQ(*cov.plan.config.start, Vec3d(0, 0, 1));
    for (const CoverageGoal& g : cov.plan.goals) {
        EXPECT_NEAR(g.tilt_deg, 20.0, 1e-4);  // stored as float
        EXPECT_NEAR((g.tool_position - g.position).norm(), 0.5, 1e-6);
    }
}

TEST_F(CliPlanes, CoverageComputesMissingPlanesFromTheCloud) {
    CliRun r = surfgrow(cat({"coverage ", q(out_)}));
    EXPECT_EQ(r.code, static_cast<int>(ErrorCode::kCannotOpen)) << r.out;
    EXPECT_NE(r.out.find("planes.json is missing"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out_ / "coverage.json"));
    r = surfgrow(cat({"coverage ", q(out_), " --cloud ", q(cloud_)}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_regular_file(out_ / "planes.json"));
    EXPECT_TRUE(fs::is_regular_file(out_ / "planes.ply"));
    EXPECT_TRUE(fs::is_regular_file(out_ / "coverage.ply"));
}

TEST_F(CliPlanes, SameBytesForAnyThreadCount) {
    for (const int t : {1, 3}) {
        const fs::path o = dir_ / cat({"t", std::to_string(t)});
        fs::copy(out_, o);
        ASSERT_EQ(surfgrow(cat({"planes ", q(o), " --cloud ", q(cloud_), " --obj --threads ",
                                std::to_string(t)}))
                      .code,
                  0);
        ASSERT_EQ(surfgrow(cat({"coverage ", q(o), " --threads ", std::to_string(t)})).code, 0);
    }
    for (const char* f :
         {"planes.json", "planes.ply", "planes.obj", "coverage.json", "coverage.ply"}) {
        EXPECT_TRUE(fs::exists(dir_ / "t1" / f)) << f;
        EXPECT_EQ(test::read_bytes(dir_ / "t1" / f), test::read_bytes(dir_ / "t3" / f)) << f;
    }
}

TEST_F(CliPlanes, MillimetreCloudsGiveTheSamePlanes) {
    io::write_cloud(dir_ / "l_mm.ply", l_cloud(1000.0));
    const fs::path mm = dir_ / "mm";
    ASSERT_EQ(surfgrow(cat({"grow ", q(dir_ / "l_mm.ply"), " -o ", q(mm),
                            " --units mm --mu 12mm --no-picture --viewpoint 0.3,0.4,0.5m -q"}))
                  .code,
              0);
    ASSERT_EQ(surfgrow(cat({"planes ", q(mm), " --cloud ", q(dir_ / "l_mm.ply"), " -q"})).code, 0);
    ASSERT_EQ(surfgrow(cat({"planes ", q(out_), " --cloud ", q(cloud_), " -q"})).code, 0);
    ASSERT_EQ(surfgrow(cat({"coverage ", q(mm), " --blast-radius 12mm -q"})).code, 0);
    ASSERT_EQ(surfgrow(cat({"coverage ", q(out_), " -q"})).code, 0);
    const auto a = io::read_planes_json(out_ / "planes.json");
    const auto b = io::read_planes_json(mm / "planes.json");
    EXPECT_EQ(b.meta.units, "mm");
    EXPECT_DOUBLE_EQ(b.planes.config.mu, 12.0);
    ASSERT_EQ(a.planes.planes.size(), b.planes.planes.size());
    // The outline follows a raster of mu / 2 cells: cells along the 1.7 m of outline and hole
    // edge that a last-bit difference in the plane's axes moves across a border change the
    // area by up to about 2 %.
    EXPECT_NEAR(b.planes.planes[0].area, 1e6 * a.planes.planes[0].area,
                0.02 * 1e6 * a.planes.planes[0].area);
    const auto ca = io::read_coverage_json(out_ / "coverage.json");
    const auto cb = io::read_coverage_json(mm / "coverage.json");
    EXPECT_DOUBLE_EQ(cb.plan.config.blast_radius, 12.0);
    EXPECT_DOUBLE_EQ(cb.plan.config.standoff, 300.0);
    EXPECT_NEAR(double(cb.plan.stats.goals), double(ca.plan.stats.goals),
                0.02 * double(ca.plan.stats.goals));
}

TEST_F(CliPlanes, AnEmptyResultGivesEmptyOutputs) {
    io::write_cloud(dir_ / "empty.ply", PointCloud{});
    const fs::path e = dir_ / "empty";
    ASSERT_EQ(
        surfgrow(cat({"grow ", q(dir_ / "empty.ply"), " -o ", q(e), " --no-picture -q"})).code, 0);
    CliRun r = surfgrow(cat({"planes ", q(e), " --cloud ", q(dir_ / "empty.ply")}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("0 surfaces -> 0 planes"), std::string::npos) << r.out;
    r = surfgrow(cat({"coverage ", q(e), " --coverage-csv"}));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(io::read_coverage_csv(e / "coverage.csv").empty());
    EXPECT_TRUE(io::read_coverage_json(e / "coverage.json").plan.goals.empty());
}

struct BadCase {
    std::string name;
    std::string command;  // with {out} and {cloud}
    ErrorCode code;
    std::string expect;
};

TEST_F(CliPlanes, BadInputsGiveClearErrorsAndLeaveOutputsAlone) {
    ASSERT_EQ(surfgrow(cat({"planes ", q(out_), " --cloud ", q(cloud_), " -q"})).code, 0);
    ASSERT_EQ(surfgrow(cat({"coverage ", q(out_), " -q"})).code, 0);
    const std::string planes_before = test::read_bytes(out_ / "planes.json");
    const std::string coverage_before = test::read_bytes(out_ / "coverage.ply");
    ASSERT_FALSE(coverage_before.empty());
    PointCloud other = l_cloud();
    other.points.resize(other.points.size() / 2);
    io::write_cloud(dir_ / "other.ply", other);
    // Same size, other points: the count of points the grower would index differs.
    PointCloud moved = l_cloud();
    for (std::size_t i = 0; i < moved.size(); i += 3) moved.points[i] = Vec3f::Constant(NAN);
    io::write_cloud(dir_ / "moved.ply", moved);
    fs::create_directories(dir_ / "notaresult");
    fs::create_directories(dir_ / "bad");
    fs::copy(out_, dir_ / "bad", fs::copy_options::recursive);
    test::write_bytes(dir_ / "bad" / "planes.json", "{\"format\": \"surfgrow-planes\"}");
    fs::create_directories(dir_ / "mismatch");
    fs::copy(out_, dir_ / "mismatch", fs::copy_options::recursive);
    {
        auto j = nlohmann::json::parse(test::read_bytes(out_ / "planes.json"));
        j["summary"]["patches"] = j["summary"]["patches"].get<int>() + 5;
        test::write_bytes(dir_ / "mismatch" / "planes.json", j.dump());
    }
    const std::string o = q(out_), c = q(cloud_);
    const std::vector<BadCase> cases = {
        {"planes without cloud", "planes " + o, ErrorCode::kUsage, "--cloud"},
        {"not a result", "planes " + q(dir_ / "notaresult") + " --cloud " + c,
         ErrorCode::kCannotOpen, "surfaces.json"},
        {"missing folder", "planes " + q(dir_ / "nope") + " --cloud " + c, ErrorCode::kCannotOpen,
         "nope"},
        {"another cloud", "planes " + o + " --cloud " + q(dir_ / "other.ply"),
         ErrorCode::kMalformedInput, "labels"},
        {"same size, other points", "planes " + o + " --cloud " + q(dir_ / "moved.ply"),
         ErrorCode::kMalformedInput, "points to grow"},
        {"offset without unit", "planes " + o + " --cloud " + c + " --offset 6", ErrorCode::kUsage,
         "unit"},
        {"offset zero", "planes " + o + " --cloud " + c + " --offset 0mm",
         ErrorCode::kInvalidParameter, "positive"},
        {"angle zero", "planes " + o + " --cloud " + c + " --angle 0", ErrorCode::kInvalidParameter,
         "angle"},
        {"angle too large", "planes " + o + " --cloud " + c + " --angle 95",
         ErrorCode::kInvalidParameter, "angle"},
        {"band reversed", "coverage " + o + " --angle-band 40:5", ErrorCode::kInvalidParameter,
         "angle band"},
        {"band syntax", "coverage " + o + " --angle-band 5-40", ErrorCode::kUsage, "MIN:MAX"},
        {"tilt outside", "coverage " + o + " --tilt 50", ErrorCode::kInvalidParameter, "tilt"},
        {"tilt negative", "coverage " + o + " --tilt=-5", ErrorCode::kInvalidParameter, "tilt"},
        {"blast zero", "coverage " + o + " --blast-radius 0mm", ErrorCode::kInvalidParameter,
         "blast"},
        {"blast without unit", "coverage " + o + " --blast-radius 12", ErrorCode::kUsage, "unit"},
        {"standoff zero", "coverage " + o + " --standoff=0m", ErrorCode::kInvalidParameter,
         "standoff"},
        {"start of two", "coverage " + o + " --start 1,2m", ErrorCode::kUsage, "--start"},
        {"broken planes.json", "coverage " + q(dir_ / "bad"), ErrorCode::kMalformedInput,
         "planes.json"},
        {"planes of another result", "coverage " + q(dir_ / "mismatch"), ErrorCode::kMalformedInput,
         "surfgrow planes"},
    };
    for (const BadCase& bc : cases) {
        const CliRun r = surfgrow(bc.command);
        EXPECT_EQ(r.code, static_cast<int>(bc.code)) << bc.name << ": " << r.out;
        EXPECT_NE(r.out.find(bc.expect), std::string::npos) << bc.name << ": " << r.out;
    }
    EXPECT_EQ(test::read_bytes(out_ / "planes.json"), planes_before);
    EXPECT_EQ(test::read_bytes(out_ / "coverage.ply"), coverage_before);
    for (const auto& e : fs::directory_iterator(out_))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace surfgrow
