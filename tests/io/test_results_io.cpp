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
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::io {
namespace {

GrowResult small_result(const GrowerConfig& cfg) {
    PointCloud cloud;
    std::mt19937_64 rng(1);
    for (const auto& f : test::box_faces({0, 0, 0}, {0.2, 0.15, 0.1}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    cloud.points.push_back(Vec3f::Constant(std::nanf("")));
    return grow_surfaces(cloud, cfg);
}

// surfaces.json and the surfaces.ply it names, as `surfgrow grow` writes them into `dir`.
void write_result_files(const std::filesystem::path& dir, const GrowResult& r,
                        const GrowerConfig& cfg, ResultMeta meta) {
    std::filesystem::create_directories(dir);
    meta.result_id = result_id(r, cfg, meta);
    write_atomically(dir / "surfaces.json",
                     [&](std::ostream& o) { write_result_json(o, r, cfg, meta); });
    write_atomically(dir / kSurfacesFile,
                     [&](std::ostream& o) { write_surfaces_ply(o, r.surfaces, meta); });
}

TEST(ResultsIo, JsonRoundTripKeepsSurfacesAndSummary) {
    GrowerConfig cfg;
    cfg.seed = 7;
    const GrowResult r = small_result(cfg);
    ASSERT_GT(r.surfaces.size(), 10u);
    ResultMeta meta;
    meta.units = "m";
    meta.offset = Vec3d(1000, -2000, 5);
    meta.input = "box.ply";
    test::TempDir dir;
    write_result_files(dir.path(), r, cfg, meta);
    const StoredResult back = read_result_json(dir / "surfaces.json");
    EXPECT_EQ(back.surfaces_file, "surfaces.ply");
    EXPECT_EQ(back.meta.units, "m");
    EXPECT_EQ(back.meta.offset, meta.offset);
    EXPECT_EQ(back.meta.input, "box.ply");
    EXPECT_EQ(back.config.mu, cfg.mu);
    EXPECT_EQ(back.config.seed, 7u);
    EXPECT_EQ(back.stats.points_in, r.stats.points_in);
    EXPECT_EQ(back.stats.invalid_points, 1u);
    EXPECT_EQ(back.stats.registered, r.stats.registered);
    ASSERT_EQ(back.surfaces.size(), r.surfaces.size());
    for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
        const Surface &a = r.surfaces[k], &b = back.surfaces[k];
        // Doubles: exact, but for adding and removing the offset (rounding).
        EXPECT_LT((a.home - b.home).norm(), 1e-9);
        EXPECT_LT((a.centroid - b.centroid).norm(), 1e-9);
        EXPECT_LT((a.bounds.min - b.bounds.min).norm(), 1e-9);
        EXPECT_LT((a.bounds.max - b.bounds.max).norm(), 1e-9);
        EXPECT_EQ(a.normal, b.normal);
        EXPECT_EQ(a.eigenvalues, b.eigenvalues);
        EXPECT_EQ(a.point_count, b.point_count);
        EXPECT_EQ(a.neighbours, b.neighbours);
        EXPECT_EQ(a.radius, b.radius);
        EXPECT_EQ(a.mean_residual, b.mean_residual);
        EXPECT_EQ(a.tolerance, b.tolerance);
    }
    // Without an offset every number comes back bit for bit.
    write_result_files(dir / "plain", r, cfg, {});
    const StoredResult plain = read_result_json(dir / "plain" / "surfaces.json");
    ASSERT_EQ(plain.surfaces.size(), r.surfaces.size());
    for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
        const Surface &a = r.surfaces[k], &b = plain.surfaces[k];
        EXPECT_EQ(a.home, b.home);
        EXPECT_EQ(a.centroid, b.centroid);
        EXPECT_EQ(a.bounds.min, b.bounds.min);
        EXPECT_EQ(a.bounds.max, b.bounds.max);
    }
}

// Version 2 keeps its surfaces in surfaces.ply: a folder whose surfaces.ply is missing, from
// another run, of another count, or not the layout is refused naming that file.
TEST(ResultsIo, SurfacesFileMustBelongToTheResult) {
    GrowerConfig cfg;
    const GrowResult r = small_result(cfg);
    test::TempDir dir;
    write_result_files(dir / "a", r, cfg, {});
    cfg.seed = 99;
    GrowResult other = small_result(cfg);
    other.surfaces.pop_back();
    write_result_files(dir / "b", other, cfg, {});
    auto refused = [&](const std::string& why, ErrorCode code, const std::string& message) {
        try {
            (void)read_result_json(dir / "a" / "surfaces.json");
            ADD_FAILURE() << "accepted " << why;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), code) << why << ": " << e.what();
            EXPECT_NE(std::string(e.what()).find("surfaces.ply"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
                << why << ": " << e.what();
        }
    };
    const std::string good = test::read_bytes(dir / "a" / "surfaces.ply");
    std::filesystem::copy_file(dir / "b" / "surfaces.ply", dir / "a" / "surfaces.ply",
                               std::filesystem::copy_options::overwrite_existing);
    refused("another run's surfaces", ErrorCode::kMalformedInput, "holds");
    // Same count, other id: refused by id.
    {
        ResultMeta m;
        m.result_id = "0123456789abcdef";
        std::ostringstream o;
        write_surfaces_ply(o, r.surfaces, m);
        test::write_bytes(dir / "a" / "surfaces.ply", o.str());
        refused("another id", ErrorCode::kMalformedInput, "another result");
    }
    test::write_bytes(dir / "a" / "surfaces.ply", good.substr(0, good.size() - 8));
    refused("truncated", ErrorCode::kMalformedInput, "truncated");
    std::string bad_normal = good;
    const std::size_t body = good.find("end_header\n") + 11;
    const double twice = 2.0;
    std::memcpy(bad_normal.data() + body + 3 * 8, &twice, sizeof twice);  // first nx
    test::write_bytes(dir / "a" / "surfaces.ply", bad_normal);
    refused("a normal of length 2", ErrorCode::kMalformedInput, "unit vector");
    std::string nan = good;
    const double not_a_number = std::nan("");
    std::memcpy(nan.data() + body, &not_a_number, sizeof not_a_number);  // first x
    test::write_bytes(dir / "a" / "surfaces.ply", nan);
    refused("NaN", ErrorCode::kMalformedInput, "not finite");
    std::string other_layout = good;
    other_layout.replace(other_layout.find("double radius"), 13, "float  radius");
    test::write_bytes(dir / "a" / "surfaces.ply", other_layout);
    refused("another layout", ErrorCode::kMalformedInput, "not a surfgrow surfaces file");
    std::filesystem::remove(dir / "a" / "surfaces.ply");
    refused("missing", ErrorCode::kCannotOpen, "");
    test::write_bytes(dir / "a" / "surfaces.ply", good);
    EXPECT_EQ(read_result_json(dir / "a" / "surfaces.json").surfaces.size(), r.surfaces.size());
}

// A version-1 folder (surfaces inline in surfaces.json) still reads.
TEST(ResultsIo, Version1SurfacesJsonStillReads) {
    const std::string v1 = R"({"format": "surfgrow-result", "version": 1, "units": "mm",
 "offset": [0, 0, 0], "input": "c.ply", "result_id": "",
 "parameters": {"mu": 12, "min_pts": 10, "alpha": 4, "plane_test": "disk",
                "plane_tolerance": 0, "mu_max": 24, "seed": 1},
 "summary": {"points_in": 100, "valid_points": 100, "invalid_points": 0, "cropped_points": 0,
             "surfaces": 1, "registered": 90, "registered_grown": 90, "noise_points": 0,
             "orientation": "up"},
 "surfaces": [{"id": 0, "plane": [0, 0, 1, -5], "normal": [0, 0, 1], "home": [1, 2, 5],
               "centroid": [1.5, 2, 5], "eigenvalues": [0, 2, 3], "radius": 12,
               "neighbours": 30, "points": 90, "mean_residual": 0.1, "tolerance": 0.5,
               "bounds": {"min": [0, 0, 5], "max": [3, 4, 5]}}]})";
    const StoredResult r = parse_result_json(v1, "old/surfaces.json");
    EXPECT_TRUE(r.surfaces_file.empty());
    ASSERT_EQ(r.surfaces.size(), 1u);
    EXPECT_EQ(r.surfaces[0].home, Vec3d(1, 2, 5));
    EXPECT_EQ(r.surfaces[0].point_count, 90u);
    EXPECT_EQ(r.surfaces[0].bounds.max, Vec3d(3, 4, 5));
}

// One reader for surfaces.json: the orientation and the workspace (viewpoint, crop) come back too,
// so a subcommand can index exactly the grown points again; broken ones are refused by name.
TEST(ResultsIo, JsonRoundTripKeepsOrientationAndWorkspace) {
    GrowerConfig cfg;
    cfg.viewpoint = Vec3d(0.1, 0.2, 1.5);
    cfg.crop.radius = 2.5;
    cfg.crop.center = Vec3d(0.1, 0.05, 0.05);
    Aabb box;
    box.add(Vec3d(-1, -1, -1));
    box.add(Vec3d(1, 1, 0.5));
    cfg.crop.box = box;
    const GrowResult r = small_result(cfg);
    ASSERT_EQ(r.stats.orientation, OrientationSource::kViewpoint);
    test::TempDir dir;
    write_result_files(dir.path(), r, cfg, {});
    const StoredResult back = read_result_json(dir / "surfaces.json");
    EXPECT_EQ(back.stats.orientation, OrientationSource::kViewpoint);
    EXPECT_EQ(back.config.viewpoint, cfg.viewpoint);
    EXPECT_EQ(back.config.crop.radius, cfg.crop.radius);
    EXPECT_EQ(back.config.crop.center, cfg.crop.center);
    ASSERT_TRUE(back.config.crop.box);
    EXPECT_EQ(back.config.crop.box->min, box.min);
    EXPECT_EQ(back.config.crop.box->max, box.max);

    // Without a crop or viewpoint nothing is invented.
    const GrowResult plain = small_result(GrowerConfig{});
    write_result_files(dir / "plain", plain, GrowerConfig{}, {});
    const StoredResult p = read_result_json(dir / "plain" / "surfaces.json");
    EXPECT_FALSE(p.config.viewpoint || p.config.crop.active());
    EXPECT_EQ(p.stats.orientation, plain.stats.orientation);

    // An unknown orientation or a crop centre that is not a point is malformed, naming the file.
    std::string text = test::read_bytes(dir / "surfaces.json");
    const std::string good = "\"orientation\": \"viewpoint\"";
    for (const auto& [from, to] :
         {std::pair<std::string, std::string>{good, "\"orientation\": \"sideways\""},
          {"\"crop_center\": [", "\"crop_center\": [\"x\", "}}) {
        std::string broken = text;
        const auto at = broken.find(from);
        ASSERT_NE(at, std::string::npos) << from << " in " << text.substr(0, 600);
        broken.replace(at, from.size(), to);
        test::write_bytes(dir / "broken.json", broken);
        try {
            (void)read_result_json(dir / "broken.json");
            ADD_FAILURE() << "accepted " << to;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kMalformedInput) << e.what();
            EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos) << e.what();
        }
    }
}

TEST(ResultsIo, SameResultSameBytes) {
    const GrowerConfig cfg;
    const GrowResult r = small_result(cfg);
    std::ostringstream a, b;
    write_result_json(a, r, cfg, {});
    write_result_json(b, small_result(cfg), cfg, {});
    EXPECT_EQ(a.str(), b.str());
    EXPECT_EQ(a.str().find("seconds"), std::string::npos);  // timings live in run.json
}

TEST(ResultsIo, SurfacesPlyHeaderAndSize) {
    const GrowerConfig cfg;
    const GrowResult r = small_result(cfg);
    std::ostringstream out;
    write_surfaces_ply(out, r.surfaces, {});
    const std::string s = out.str();
    const auto end = s.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    EXPECT_NE(s.find("element vertex " + std::to_string(r.surfaces.size()) + "\n"),
              std::string::npos);
    EXPECT_NE(s.find("property double nx\n"), std::string::npos);
    const std::size_t record = 22 * 8 + 2 * 4;
    EXPECT_EQ(s.size() - (end + 11), r.surfaces.size() * record);
    // First vertex's position and normal, read back from the bytes.
    double v[6];
    std::memcpy(v, s.data() + end + 11, sizeof v);
    EXPECT_EQ(v[0], r.surfaces[0].home.x());
    EXPECT_EQ(v[5], r.surfaces[0].normal.z());
    // With an offset, positions carry it.
    std::ostringstream wide;
    ResultMeta meta;
    meta.offset = Vec3d(500000, 5400000, 300);
    write_surfaces_ply(wide, r.surfaces, meta);
    const std::string w = wide.str();
    double x = 0;
    std::memcpy(&x, w.data() + w.find("end_header\n") + 11, sizeof x);
    EXPECT_DOUBLE_EQ(x, r.surfaces[0].home.x() + 500000);
    // The generic cloud reader (Open3D's, PCL's) sees a cloud with normals.
    test::TempDir dir;
    test::write_bytes(dir / "surfaces.ply", s);
    const PointCloud back = read_cloud(dir / "surfaces.ply");
    ASSERT_EQ(back.size(), r.surfaces.size());
    ASSERT_EQ(back.normals.size(), r.surfaces.size());
    EXPECT_FLOAT_EQ(back.normals[0].z(), static_cast<float>(r.surfaces[0].normal.z()));
}

TEST(ResultsIo, LabelsRoundTrip) {
    const std::vector<std::int32_t> labels = {-1, 0, 5, 2147483647, -1, 12};
    test::TempDir dir;
    write_atomically(dir / "labels.txt", [&](std::ostream& o) { write_labels_txt(o, labels); });
    EXPECT_EQ(test::read_bytes(dir / "labels.txt"), "-1\n0\n5\n2147483647\n-1\n12\n");
    EXPECT_EQ(read_labels_txt(dir / "labels.txt"), labels);
    // labels.bin: the int32s themselves, little-endian; read_labels picks the reader by name.
    write_atomically(dir / "labels.bin", [&](std::ostream& o) { write_labels_bin(o, labels); });
    const std::string bytes = test::read_bytes(dir / "labels.bin");
    ASSERT_EQ(bytes.size(), 4 * labels.size());
    EXPECT_EQ(bytes.substr(0, 8), std::string("\xff\xff\xff\xff\x00\x00\x00\x00", 8));
    EXPECT_EQ(read_labels(dir / "labels.bin"), labels);
    EXPECT_EQ(read_labels(dir / "labels.txt"), labels);
    EXPECT_EQ(labels_file(dir.path()), dir / "labels.bin");
    std::filesystem::remove(dir / "labels.bin");
    EXPECT_EQ(labels_file(dir.path()), dir / "labels.txt");  // a folder from before labels.bin
    // A size that is not whole labels, an id below -1: refused by name.
    for (const std::string& bad :
         {std::string("\x01\x00\x00", 3), std::string("\xfe\xff\xff\xff", 4)}) {
        try {
            (void)parse_labels_bin(bad, "out/labels.bin");
            ADD_FAILURE() << bad.size();
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kMalformedInput);
            EXPECT_NE(std::string(e.what()).find("out/labels.bin"), std::string::npos) << e.what();
        }
    }
    EXPECT_TRUE(parse_labels_bin("", "empty").empty());
}

TEST(ResultsIo, CsvHasOneRowPerSurface) {
    const GrowerConfig cfg;
    const GrowResult r = small_result(cfg);
    std::ostringstream out;
    write_surfaces_csv(out, r.surfaces, {});
    const std::string s = out.str();
    EXPECT_EQ(static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')),
              r.surfaces.size() + 1);
    EXPECT_EQ(s.rfind("id,home_x", 0), 0u);
}

TEST(ResultsIo, BadResultFilesAreRejectedClearly) {
    test::TempDir dir;
    auto expect_code = [](const std::filesystem::path& f, ErrorCode code) {
        try {
            (void)read_result_json(f);
            ADD_FAILURE() << "accepted " << f;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), code) << e.what();
            EXPECT_NE(std::string(e.what()).find(f.filename().string()), std::string::npos)
                << e.what();
        }
    };
    expect_code(dir / "missing.json", ErrorCode::kCannotOpen);
    test::write_bytes(dir / "garbage.json", "{not json");
    expect_code(dir / "garbage.json", ErrorCode::kMalformedInput);
    test::write_bytes(dir / "other.json", R"({"format": "something-else"})");
    expect_code(dir / "other.json", ErrorCode::kMalformedInput);
    test::write_bytes(dir / "short.json", R"({"format": "surfgrow-result", "units": "m"})");
    expect_code(dir / "short.json", ErrorCode::kMalformedInput);
    // A count no integer type holds (fuzz/crashes/surfaces_json: converting 2e107 to a count
    // was undefined behaviour), a negative one, a fraction: refused by name.
    {
        const GrowerConfig cfg;
        const GrowResult r = small_result(cfg);
        ResultMeta meta;
        meta.units = "m";
        std::ostringstream out;
        write_result_json(out, r, cfg, meta);
        const auto good = nlohmann::json::parse(out.str());
        const std::vector<nlohmann::json> bad_counts = {2.3e107, -3, 0.5};
        for (const nlohmann::json& bad : bad_counts) {
            nlohmann::json j = good;
            j["summary"]["valid_points"] = bad;
            test::write_bytes(dir / "count.json", j.dump());
            expect_code(dir / "count.json", ErrorCode::kMalformedInput);
            try {
                (void)read_result_json(dir / "count.json");
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("valid_points must be a whole number"),
                          std::string::npos)
                    << e.what();
            }
        }
    }
    test::write_bytes(dir / "labels.txt", "0\n1\nbanana\n");
    try {
        (void)read_labels_txt(dir / "labels.txt");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kMalformedInput);
        EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos);
    }
}

TEST(AtomicOutput, CommitPublishesEveryFile) {
    test::TempDir dir;
    OutputTransaction tx(dir / "out");
    tx.add("a.txt", [](std::ostream& o) { o << "A"; });
    tx.add("b.txt", [](std::ostream& o) { o << "B"; });
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "a.txt"));
    tx.commit();
    EXPECT_EQ(test::read_bytes(dir / "out" / "a.txt"), "A");
    EXPECT_EQ(test::read_bytes(dir / "out" / "b.txt"), "B");
}

TEST(AtomicOutput, UnwritableDestinationsReportCannotWrite) {
    test::TempDir dir;
    test::write_bytes(dir / "file", "x");
    try {
        OutputTransaction tx(dir / "file");  // a file where a folder should be
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotWrite);
    }
    try {
        write_atomically(dir / "no" / "such" / "folder.txt", [](std::ostream& o) { o << "x"; });
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotWrite);
    }
}

}  // namespace
}  // namespace surfgrow::io
