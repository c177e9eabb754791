// planes.json, planes.ply/obj, coverage.json/csv: round trips, determinism and bad shapes.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"

namespace surfgrow::io {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Fixture {
    PointCloud cloud;
    GrowResult grown;
    BoundPlanes planes;
    CoveragePlan plan;
};

// An L of two plates, the floor with a square hole.
const Fixture& fixture() {
    static const Fixture f = [] {
        Fixture x;
        std::mt19937_64 rng(5);
        std::vector<Vec3f> pts;
        test::sample_rect({{0.2, 0.15, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15}, 0.005, 0.3,
                          0.001, rng, pts);
        test::sample_rect({{0, 0.15, 0.15}, Vec3d::UnitY(), Vec3d::UnitZ(), 0.15, 0.15}, 0.005, 0.3,
                          0.001, rng, pts);
        for (const Vec3f& p : pts)
            if (!(p.z() < 0.01f && std::abs(p.x() - 0.25f) < 0.04f &&
                  std::abs(p.y() - 0.15f) < 0.04f))
                x.cloud.points.push_back(p);
        x.cloud.viewpoint = Vec3d(0.3, 0.4, 0.5);
        x.grown = grow_surfaces(x.cloud, GrowerConfig{});
        x.planes = compute_bound_planes(x.cloud, x.grown, BoundPlaneConfig{});
        x.plan = plan_coverage(x.planes, x.grown, CoverageConfig{});
        return x;
    }();
    return f;
}

ResultMeta georeferenced() {
    ResultMeta m;
    m.units = "m";
    m.offset = Vec3d(500000, 4000000, 100);
    m.input = "scan.ply";
    return m;
}

template <class F>
std::string bytes_of(F&& write) {
    std::ostringstream s;
    write(s);
    return s.str();
}

ErrorCode code_of(const std::function<void()>& f, std::string* message = nullptr) {
    try {
        f();
    } catch (const Error& e) {
        if (message) *message = e.what();
        return e.code();
    }
    return ErrorCode::kInternal;
}

TEST(PlanesIo, JsonRoundTripKeepsEveryPlane) {
    const Fixture& f = fixture();
    ASSERT_GE(f.planes.planes.size(), 2u);
    test::TempDir dir;
    const ResultMeta meta = georeferenced();
    write_atomically(dir / "planes.json",
                     [&](std::ostream& o) { write_planes_json(o, f.planes, meta); });
    const StoredPlanes back = read_planes_json(dir / "planes.json");
    EXPECT_EQ(back.meta.offset, meta.offset);
    EXPECT_EQ(back.meta.input, "scan.ply");
    EXPECT_EQ(back.planes.config.max_offset, f.planes.config.max_offset);
    EXPECT_EQ(back.planes.config.max_gap, f.planes.config.max_gap);
    EXPECT_EQ(back.planes.stats.patches, f.planes.stats.patches);
    EXPECT_EQ(back.planes.plane_of_patch, f.planes.plane_of_patch);
    ASSERT_EQ(back.planes.planes.size(), f.planes.planes.size());
    for (std::size_t k = 0; k < f.planes.planes.size(); ++k) {
        const BoundPlane &a = f.planes.planes[k], &b = back.planes.planes[k];
        EXPECT_EQ(a.normal, b.normal);
        EXPECT_LT((a.centroid - b.centroid).norm(), 1e-9);  // through the offset and back
        EXPECT_EQ(a.u_axis, b.u_axis);
        EXPECT_EQ(a.area, b.area);
        EXPECT_EQ(a.point_count, b.point_count);
        EXPECT_EQ(a.patches, b.patches);
        ASSERT_EQ(a.polygons.size(), b.polygons.size());
        for (std::size_t q = 0; q < a.polygons.size(); ++q) {
            EXPECT_EQ(a.polygons[q].outer, b.polygons[q].outer);
            EXPECT_EQ(a.polygons[q].holes, b.polygons[q].holes);
        }
    }
    // The plane equation is written in file coordinates.
    const json j = json::parse(test::read_bytes(dir / "planes.json"));
    const auto& p0 = j["planes"][0];
    const Vec3d c(p0["centroid"][0].get<double>(), p0["centroid"][1].get<double>(),
                  p0["centroid"][2].get<double>());
    const Vec3d n(p0["plane"][0].get<double>(), p0["plane"][1].get<double>(),
                  p0["plane"][2].get<double>());
    EXPECT_NEAR(n.dot(c) + p0["plane"][3].get<double>(), 0.0, 1e-6);
    // Same planes, same bytes.
    EXPECT_EQ(bytes_of([&](std::ostream& o) { write_planes_json(o, f.planes, meta); }),
              test::read_bytes(dir / "planes.json"));
}

TEST(PlanesIo, BadPlanesFilesAreRefusedWithTheProblemNamed) {
    const Fixture& f = fixture();
    test::TempDir dir;
    const json good =
        json::parse(bytes_of([&](std::ostream& o) { write_planes_json(o, f.planes, {}); }));
    struct Case {
        const char* name;
        std::function<void(json&)> mutate;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {"format", [](json& j) { j["format"] = "surfgrow-result"; }, "not a surfgrow planes"},
        {"ring of two",
         [](json& j) {
             auto& ring = j["planes"][0]["polygons"][0]["outer"];
             ring = json::array({ring[0], ring[1]});
         },
         "at least 3"},
        {"vertex of one number", [](json& j) { j["planes"][0]["polygons"][0]["outer"][1] = {1.0}; },
         "not [a, b]"},
        {"vertex not a number", [](json& j) { j["planes"][0]["polygons"][0]["outer"][1][0] = "x"; },
         "not [a, b]"},
        {"normal not unit",
         [](json& j) {
             j["planes"][0]["normal"] = {0, 0, 2};
         },
         "unit"},
        {"normal of two",
         [](json& j) {
             j["planes"][1]["normal"] = {0, 1};
         },
         "plane 1"},
        {"axes crossed", [](json& j) { j["planes"][0]["v_axis"] = j["planes"][0]["u_axis"]; },
         "axes"},
        {"patch twice",
         [](json& j) { j["planes"][1]["patches"][0] = j["planes"][0]["patches"][0]; },
         "already in plane"},
        {"patch beyond", [](json& j) { j["planes"][0]["patches"][0] = 1u << 30; }, "beyond"},
        {"count", [](json& j) { j["summary"]["planes"] = 999; }, "999 planes"},
        {"missing field", [](json& j) { j["planes"][0].erase("polygons"); }, "polygons"},
        {"negative area", [](json& j) { j["planes"][0]["area"] = -1; }, "area"},
        {"holes not a list", [](json& j) { j["planes"][0]["polygons"][0]["holes"] = 3; }, "holes"},
        // Counts and ids that no integer type holds (fuzz/crashes/planes_json): converting them
        // was undefined behaviour.
        {"count a huge float", [](json& j) { j["summary"]["patches_merged"] = 1.5e116; },
         "patches_merged must be a whole number"},
        {"count a fraction", [](json& j) { j["summary"]["points"] = 2.5; },
         "points must be a whole number"},
        {"count negative", [](json& j) { j["summary"]["degenerate"] = -1; },
         "degenerate must be a whole number"},
        {"patch id a float", [](json& j) { j["planes"][0]["patches"][0] = 1e30; },
         "patch id must be a whole number"},
        {"version a float", [](json& j) { j["version"] = 1e300; }, "version must be"},
    };
    for (const Case& c : cases) {
        json j = good;
        c.mutate(j);
        test::write_bytes(dir / "planes.json", j.dump());
        std::string message;
        EXPECT_EQ(code_of([&] { (void)read_planes_json(dir / "planes.json"); }, &message),
                  ErrorCode::kMalformedInput)
            << c.name;
        EXPECT_NE(message.find(c.expect), std::string::npos) << c.name << ": " << message;
        EXPECT_NE(message.find("planes.json"), std::string::npos) << c.name;
    }
    test::write_bytes(dir / "planes.json", "{ not json");
    EXPECT_EQ(code_of([&] { (void)read_planes_json(dir / "planes.json"); }),
              ErrorCode::kMalformedInput);
    EXPECT_EQ(code_of([&] { (void)read_planes_json(dir / "missing.json"); }),
              ErrorCode::kCannotOpen);
    EXPECT_EQ(code_of([&] { (void)read_planes_json(dir.path()); }), ErrorCode::kCannotOpen);
}

TEST(PlanesIo, MeshRoundTripsThroughPlyAndOpensAsACloud) {
    const Fixture& f = fixture();
    const PlaneMesh mesh = mesh_bound_planes(f.planes);
    ASSERT_FALSE(mesh.triangles.empty());
    test::TempDir dir;
    for (const ResultMeta& meta : {ResultMeta{}, georeferenced()}) {
        write_atomically(dir / "planes.ply",
                         [&](std::ostream& o) { write_planes_ply(o, mesh, meta); });
        const PlaneMesh back = read_planes_ply(dir / "planes.ply", meta.offset);
        ASSERT_EQ(back.vertices.size(), mesh.vertices.size());
        EXPECT_EQ(back.triangles, mesh.triangles);
        EXPECT_EQ(back.triangle_plane, mesh.triangle_plane);
        EXPECT_EQ(back.vertex_plane, mesh.vertex_plane);
        for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
            ASSERT_LT((back.vertices[i] - mesh.vertices[i]).norm(), 1e-6);
        // Generic PLY readers see its vertices (Open3D, PCL, CloudCompare read it likewise).
        EXPECT_EQ(read_cloud(dir / "planes.ply").size(), mesh.vertices.size());
    }
    // Broken files.
    const std::string bytes = test::read_bytes(dir / "planes.ply");
    test::write_bytes(dir / "cut.ply", bytes.substr(0, bytes.size() - 7));
    EXPECT_EQ(code_of([&] { (void)read_planes_ply(dir / "cut.ply"); }), ErrorCode::kMalformedInput);
    std::string bad_index = bytes;
    const std::size_t face = bad_index.size() - 17;  // the last face: count, 3 indices, plane
    bad_index[face + 1] = '\xff';
    bad_index[face + 2] = '\xff';
    bad_index[face + 3] = '\xff';
    bad_index[face + 4] = '\x7f';
    test::write_bytes(dir / "index.ply", bad_index);
    std::string message;
    EXPECT_EQ(code_of([&] { (void)read_planes_ply(dir / "index.ply"); }, &message),
              ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("refers to vertex"), std::string::npos) << message;
    // Found by fuzz/planes_ply: a vertex's plane id of 2^31 - 1 made the reader allocate 48 GiB
    // for plane normals; an id beyond what the file could hold is refused.
    std::string bad_plane = bytes;
    const bool wide = bytes.find("property double x") != std::string::npos;
    const std::size_t vertex_plane =  // the first vertex's plane: after x y z and nx ny nz
        bytes.find("end_header\n") + 11 + (wide ? 24 : 12) + 12;
    for (int k = 0; k < 4; ++k) bad_plane[vertex_plane + k] = k == 3 ? '\x7f' : '\xff';
    test::write_bytes(dir / "plane.ply", bad_plane);
    EXPECT_EQ(code_of([&] { (void)read_planes_ply(dir / "plane.ply"); }, &message),
              ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("more planes than the file could hold"), std::string::npos) << message;
    PointCloud c;
    c.points = {{0, 0, 0}, {1, 0, 0}};
    write_cloud(dir / "cloud.ply", c);
    EXPECT_EQ(code_of([&] { (void)read_planes_ply(dir / "cloud.ply", {}); }, &message),
              ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("not a surfgrow planes mesh"), std::string::npos) << message;
}

TEST(PlanesIo, ObjHasOneObjectPerPlane) {
    const Fixture& f = fixture();
    const PlaneMesh mesh = mesh_bound_planes(f.planes);
    const std::string text =
        bytes_of([&](std::ostream& o) { write_planes_obj(o, mesh, georeferenced()); });
    std::istringstream in(text);
    std::string line;
    std::size_t v = 0, vn = 0, faces = 0, objects = 0;
    while (std::getline(in, line)) {
        v += line.rfind("v ", 0) == 0;
        vn += line.rfind("vn ", 0) == 0;
        faces += line.rfind("f ", 0) == 0;
        objects += line.rfind("o plane_", 0) == 0;
    }
    EXPECT_EQ(v, mesh.vertices.size());
    EXPECT_EQ(vn, f.planes.planes.size());
    EXPECT_EQ(faces, mesh.triangles.size());
    std::set<std::uint32_t> with_triangles(mesh.triangle_plane.begin(), mesh.triangle_plane.end());
    EXPECT_EQ(objects, with_triangles.size());
}

// coverage.json as version 1 wrote it (goals inline), from the version 2 file and the plan: a
// result folder of an older surfgrow.
json coverage_json_v1(const CoveragePlan& plan, const ResultMeta& meta) {
    json j = json::parse(bytes_of([&](std::ostream& o) { write_coverage_json(o, plan, meta); }));
    j["version"] = 1;
    j.erase("goals_file");
    auto vec = [](const Vec3d& v) { return json::array({v.x(), v.y(), v.z()}); };
    json goals = json::array();
    for (std::size_t k = 0; k < plan.goals.size(); ++k) {
        const CoverageGoal& g = plan.goals[k];
        const Eigen::Quaterniond& q = g.orientation;
        goals.push_back({{"seq", k},
                         {"plane", g.plane},
                         {"row", g.row},
                         {"position", vec(g.position + meta.offset)},
                         {"normal", vec(g.normal)},
                         {"direction", vec(g.direction)},
                         {"tool_position", vec(g.tool_position + meta.offset)},
                         {"tool_axis", vec(g.tool_axis)},
                         {"orientation", {q.w(), q.x(), q.y(), q.z()}},
                         {"tilt_deg", g.tilt_deg},
                         {"from_home", g.from_home},
                         {"transition", g.transition}});
    }
    j["goals"] = goals;
    return j;
}

// Goals read back from the binary file (floats for unit vectors; positions in float, or double
// when georeferenced) and from text (exact to the digits printed).
void expect_same_goals(const std::vector<CoverageGoal>& back, const CoveragePlan& plan,
                       double position_tol, double unit_tol, const char* what) {
    ASSERT_EQ(back.size(), plan.goals.size()) << what;
    for (std::size_t k = 0; k < plan.goals.size(); ++k) {
        const CoverageGoal &g = back[k], &a = plan.goals[k];
        EXPECT_EQ(g.plane, a.plane) << what;
        EXPECT_EQ(g.row, a.row) << what;
        EXPECT_LT((g.position - a.position).norm(), position_tol) << what << " goal " << k;
        EXPECT_LT((g.tool_position - a.tool_position).norm(), position_tol) << what;
        EXPECT_LT((g.normal - a.normal).norm(), unit_tol) << what;
        EXPECT_LT((g.tool_axis - a.tool_axis).norm(), unit_tol) << what;
        EXPECT_LT((g.orientation.coeffs() - a.orientation.coeffs()).norm(), unit_tol) << what;
        EXPECT_NEAR(g.tilt_deg, a.tilt_deg, 1e-4) << what;
        EXPECT_EQ(g.transition, a.transition) << what;
        EXPECT_EQ(g.from_home, a.from_home) << what;
    }
}

TEST(CoverageIo, JsonPlyAndCsvRoundTrip) {
    const Fixture& f = fixture();
    const CoveragePlan& plan = f.plan;
    ASSERT_GT(plan.goals.size(), 100u);
    for (const ResultMeta& meta : {georeferenced(), ResultMeta{}}) {
        const bool wide = meta.offset != Vec3d::Zero();
        test::TempDir dir;
        write_atomically(dir / "coverage.json",
                         [&](std::ostream& o) { write_coverage_json(o, plan, meta); });
        write_atomically(dir / "coverage.ply",
                         [&](std::ostream& o) { write_coverage_ply(o, plan, meta); });
        write_atomically(dir / "coverage.csv",
                         [&](std::ostream& o) { write_coverage_csv(o, plan, meta); });
        const StoredCoverage back = read_coverage_json(dir / "coverage.json");
        EXPECT_EQ(back.goals_file, "coverage.ply");
        EXPECT_EQ(back.plan.stats.goals, plan.stats.goals);
        EXPECT_EQ(back.plan.stats.coverage, plan.stats.coverage);
        EXPECT_EQ(back.plan.stats.tool_path_length, plan.stats.tool_path_length);
        EXPECT_EQ(back.plan.config.blast_radius, plan.config.blast_radius);
        EXPECT_EQ(back.plan.per_plane.size(), plan.per_plane.size());
        expect_same_goals(back.plan.goals, plan, wide ? 1e-8 : 1e-5, 1e-6, "coverage.ply");
        expect_same_goals(read_coverage_csv(dir / "coverage.csv", meta.offset), plan, 1e-8, 1e-12,
                          "coverage.csv");
        // Binary: far smaller than the text it replaces.
        EXPECT_LT(fs::file_size(dir / "coverage.ply") * 2, fs::file_size(dir / "coverage.csv"));
        // An older folder's coverage.json, goals inline, still reads.
        test::write_bytes(dir / "coverage.json", coverage_json_v1(plan, meta).dump());
        fs::remove(dir / "coverage.ply");
        const StoredCoverage v1 = read_coverage_json(dir / "coverage.json");
        EXPECT_TRUE(v1.goals_file.empty());
        expect_same_goals(v1.plan.goals, plan, 1e-8, 1e-12, "version 1");
    }
}

TEST(CoverageIo, BadRobotFilesAreRefusedWithTheLineNamed) {
    const Fixture& f = fixture();
    test::TempDir dir;
    const std::string csv =
        bytes_of([&](std::ostream& o) { write_coverage_csv(o, f.plan, ResultMeta{}); });
    const std::string header = csv.substr(0, csv.find('\n') + 1);
    const std::string row =
        csv.substr(header.size(), csv.find('\n', header.size()) + 1 - header.size());
    struct Case {
        const char* name;
        std::string text;
        const char* expect;
    };
    std::string short_row = row.substr(0, row.rfind(',')) + "\n";
    std::string word_row = row;
    word_row.replace(word_row.find(',', word_row.find(',') + 1) + 1, 1, "x");
    std::string long_row = row;
    long_row.insert(long_row.size() - 1, ",1");
    const std::vector<Case> cases = {
        {"header", "x,y,z\n" + row, "header"},
        {"short row", header + row + short_row, "line 3: 21 fields"},
        {"long row", header + long_row, "line 2: more than 22"},
        {"word", header + word_row, "is not a finite number"},
        {"axis", header + "0,0,0,0,0,0,0,0,1,0,0,1,0,0,-2,1,0,0,0,5,0,0\n", "tool axis"},
        {"quaternion", header + "0,0,0,0,0,0,0,0,1,0,0,1,0,0,-1,2,0,0,0,5,0,0\n", "quaternion"},
        {"negative plane", header + "0,-1,0,0,0,0,0,0,1,0,0,1,0,0,-1,1,0,0,0,5,0,0\n", "whole"},
        // Found by fuzz/coverage_csv: an id beyond 32 bits was converted to uint32 (UB).
        {"huge plane", header + "0,1e20,0,0,0,0,0,0,1,0,0,1,0,0,-1,1,0,0,0,5,0,0\n", "2^32 - 1"},
        {"huge row", header + "0,0,4294967296,0,0,0,0,0,1,0,0,1,0,0,-1,1,0,0,0,5,0,0\n", "whole"},
    };
    for (const Case& c : cases) {
        test::write_bytes(dir / "coverage.csv", c.text);
        std::string message;
        EXPECT_EQ(code_of([&] { (void)read_coverage_csv(dir / "coverage.csv"); }, &message),
                  ErrorCode::kMalformedInput)
            << c.name;
        EXPECT_NE(message.find(c.expect), std::string::npos) << c.name << ": " << message;
    }
    // JSON (version 1, goals inline): wrong shapes.
    const json good = coverage_json_v1(f.plan, ResultMeta{});
    const std::vector<std::pair<std::function<void(json&)>, const char*>> mutations = {
        {[](json& j) {
             j["goals"][3]["position"] = {1, 2};
         },
         "goal 3"},
        {[](json& j) {
             j["goals"][0]["orientation"] = {1, 0, 0};
         },
         "orientation"},
        {[](json& j) {
             j["goals"][0]["tool_axis"] = {0, 0, 3};
         },
         "unit"},
        {[](json& j) { j["goals"].erase(0); }, "summary says"},
        {[](json& j) {
             j["parameters"]["angle_band_deg"] = {50, 40};
         },
         "angle band"},
        {[](json& j) { j["format"] = "surfgrow-planes"; }, "not a surfgrow coverage"},
    };
    for (const auto& [mutate, expect] : mutations) {
        json j = good;
        mutate(j);
        test::write_bytes(dir / "coverage.json", j.dump());
        std::string message;
        EXPECT_EQ(code_of([&] { (void)read_coverage_json(dir / "coverage.json"); }, &message),
                  ErrorCode::kMalformedInput)
            << expect;
        EXPECT_NE(message.find(expect), std::string::npos) << message;
    }
    EXPECT_EQ(code_of([&] { (void)read_coverage_csv(dir / "none.csv"); }), ErrorCode::kCannotOpen);

    // Version 2: the goals file it names, and what that holds.
    ResultMeta meta;
    meta.result_id = "0123456789abcdef";
    const std::string v2 = bytes_of([&](std::ostream& o) { write_coverage_json(o, f.plan, meta); });
    const std::string ply = bytes_of([&](std::ostream& o) { write_coverage_ply(o, f.plan, meta); });
    const auto read_v2 = [&](const std::string& json_text, const std::string& ply_bytes,
                             std::string* message) {
        test::write_bytes(dir / "coverage.json", json_text);
        fs::remove(dir / "coverage.ply");
        if (!ply_bytes.empty()) test::write_bytes(dir / "coverage.ply", ply_bytes);
        return code_of([&] { (void)read_coverage_json(dir / "coverage.json"); }, message);
    };
    std::string message;
    EXPECT_EQ(read_v2(v2, "", &message), ErrorCode::kCannotOpen);
    EXPECT_NE(message.find("coverage.ply"), std::string::npos) << message;
    json outside = json::parse(v2);
    outside["goals_file"] = "../coverage.ply";
    EXPECT_EQ(read_v2(outside.dump(), ply, &message), ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("beside it"), std::string::npos) << message;
    ResultMeta other = meta;
    other.result_id = "fedcba9876543210";
    EXPECT_EQ(read_v2(v2, bytes_of([&](std::ostream& o) { write_coverage_ply(o, f.plan, other); }),
                      &message),
              ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("another plan"), std::string::npos) << message;
    CoveragePlan fewer = f.plan;
    fewer.goals.pop_back();
    EXPECT_EQ(read_v2(v2, bytes_of([&](std::ostream& o) { write_coverage_ply(o, fewer, meta); }),
                      &message),
              ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("goals but"), std::string::npos) << message;
    json newer = json::parse(v2);
    newer["version"] = 3;
    EXPECT_EQ(read_v2(newer.dump(), ply, &message), ErrorCode::kMalformedInput);
    EXPECT_NE(message.find("versions 1 and 2"), std::string::npos) << message;
    // The binary goals: truncated, another layout, a value that is not finite, not unit.
    const std::size_t body = ply.find("end_header\n") + 11;
    const std::size_t stride = (ply.size() - body) / f.plan.goals.size();
    std::string nan_goal = ply, long_normal = ply, other_layout = ply;
    const float nan = std::numeric_limits<float>::quiet_NaN(), two = 2.0f;
    std::memcpy(nan_goal.data() + body + 5 * stride, &nan, 4);          // goal 5's x
    std::memcpy(long_normal.data() + body + 2 * stride + 12, &two, 4);  // goal 2's nx
    other_layout.replace(other_layout.find("float tilt_deg"), 14, "float tilt_rad");
    const std::vector<std::pair<std::string, const char*>> plys = {
        {ply.substr(0, ply.size() - 1), "truncated"},
        {ply + "x", "too long"},
        {other_layout, "layout"},
        {nan_goal, "goal 5 is not finite"},
        {long_normal, "goal 2: its normal"},
        {"ply\nformat ascii 1.0\nend_header\n", "layout"},
        {"not a ply", "not a PLY"},
    };
    for (const auto& [bytes, expect] : plys) {
        EXPECT_EQ(code_of([&] { (void)parse_coverage_ply(bytes, "coverage.ply"); }, &message),
                  ErrorCode::kMalformedInput)
            << expect;
        EXPECT_NE(message.find(expect), std::string::npos) << expect << ": " << message;
    }
}

}  // namespace
}  // namespace surfgrow::io
