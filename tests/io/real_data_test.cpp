// The real third-party scans in ../shared/data/real: every PCD reads with the point count, the
// labels and the extent its README lists. Skipped where the folder is absent (a user's clone).
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "io_test_helpers.hpp"
#include "support/test_support.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::test {
namespace {

namespace fs = std::filesystem;

// Point counts as the README lists them, file by file.
const std::map<std::string, std::size_t>& listed_counts() {
    static const std::map<std::string, std::size_t> counts{
        {"pcl_data/tutorials/room_scan1.pcd", 112586},
        {"pcl_data/tutorials/room_scan2.pcd", 112624},
        {"plane_seg/terrain_med.pcd", 68913},
        {"plane_seg/terrain_close_rect.pcd", 90227},
        {"plane_seg/tilted-steps.pcd", 181648},
        {"bobkov_segmentation/room1_gt_fine.pcd", 237907},
        {"bobkov_segmentation/room2_gt_coarse.pcd", 123692},
        {"bobkov_segmentation/room2_gt_fine.pcd", 123692},
        {"pcl_test/sac_plane_test.pcd", 3283},
        {"pcl_test/bun0.pcd", 397},
        {"pcl_data/terrain/CSite2_orig-utm.pcd", 486800},
        {"pcl_data/terrain/FSite8_orig-utm.pcd", 345966},
        {"pcl_data/tutorials/min_cut_segmentation_tutorial.pcd", 9311},
        {"pcl_data/terrain/samp24-utm.pcd", 7492},
        {"pcl_data/terrain/samp12-utm.pcd", 52119},
        {"pcl_data/terrain/samp54-utm-ground.pcd", 3983},
        {"pcl_data/terrain/samp61-utm-ground.pcd", 33854},
    };
    return counts;
}

std::string name_in(const fs::path& file, const fs::path& root) {
    return fs::relative(file, root).generic_string();
}

TEST(RealData, EveryPcdReadsWithTheListedPointCount) {
    const auto root = real_data_dir();
    if (!root) GTEST_SKIP() << "no ../shared/data/real";
    std::size_t files = 0;
    std::set<std::string> seen;
    for (const auto& entry : fs::recursive_directory_iterator(*root)) {
        if (entry.path().extension() != ".pcd") continue;
        const std::string name = name_in(entry.path(), *root);
        SCOPED_TRACE(name);
        const PointCloud cloud = io::read_cloud(entry.path());
        ++files;
        seen.insert(name);
        // Float files keep a zero offset (the ISPRS UTM ones included: float32 in the file).
        EXPECT_EQ(cloud.offset, Vec3d::Zero());
        EXPECT_FALSE(cloud.viewpoint.has_value());  // all carry the default or none
        const auto listed = listed_counts().find(name);
        if (listed != listed_counts().end()) {
            EXPECT_EQ(cloud.size(), listed->second);
        } else if (name.find("-utm-ground.pcd") != std::string::npos) {
            // The README gives the ground files' range: 3,983 to 33,854 points.
            EXPECT_GE(cloud.size(), 3983u);
            EXPECT_LE(cloud.size(), 33854u);
        } else {
            // ... and the samples': 7,492 (samp24) to 52,119 (samp12).
            ASSERT_NE(name.find("/samp"), std::string::npos) << "a file the README does not list";
            EXPECT_GE(cloud.size(), 7492u);
            EXPECT_LE(cloud.size(), 52119u);
        }
    }
    // The README's "44 data files" are these 43 PCDs and terrain/README.upstream.md.
    EXPECT_EQ(files, 43u);
    for (const auto& [name, count] : listed_counts()) EXPECT_TRUE(seen.count(name)) << name;
}

std::size_t distinct(const std::vector<int32_t>& labels) {
    return std::set<int32_t>(labels.begin(), labels.end()).size();
}

TEST(RealData, BobkovGroundTruthLabels) {
    const auto root = real_data_dir();
    if (!root) GTEST_SKIP() << "no ../shared/data/real";
    const fs::path dir = *root / "bobkov_segmentation";
    // room1 is binary with 3,910 zero bytes of PCL padding after its points.
    const PointCloud room1 = io::read_cloud(dir / "room1_gt_fine.pcd");
    ASSERT_TRUE(room1.has_labels());
    EXPECT_EQ(distinct(room1.labels), 45u);
    EXPECT_EQ(std::count(room1.labels.begin(), room1.labels.end(), 0), 117082);
    const PointCloud coarse = io::read_cloud(dir / "room2_gt_coarse.pcd");
    const PointCloud fine = io::read_cloud(dir / "room2_gt_fine.pcd");
    EXPECT_EQ(distinct(coarse.labels), 14u);
    EXPECT_EQ(distinct(fine.labels), 49u);
    // The same points, labelled twice.
    ASSERT_EQ(coarse.size(), fine.size());
    EXPECT_TRUE(std::equal(coarse.points.begin(), coarse.points.end(), fine.points.begin()));
    io::ReadOptions no_labels;
    no_labels.read_labels = false;
    EXPECT_TRUE(io::read_cloud(dir / "room2_gt_fine.pcd", no_labels).labels.empty());
}

TEST(RealData, ExtentsMatchTheReadme) {
    const auto root = real_data_dir();
    if (!root) GTEST_SKIP() << "no ../shared/data/real";
    const struct {
        const char* file;
        Vec3d extent;
    } cases[] = {
        {"pcl_data/tutorials/room_scan1.pcd", {29.2, 14.5, 3.1}},  // binary_compressed
        {"plane_seg/terrain_med.pcd", {6.4, 6.1, 3.4}},            // binary, VERSION .7
        {"plane_seg/terrain_close_rect.pcd", {5.3, 5.7, 2.5}},     // ascii
        {"pcl_data/tutorials/min_cut_segmentation_tutorial.pcd", {8.0, 7.3, 1.8}},  // CRLF
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file);
        const PointCloud cloud = io::read_cloud(*root / c.file);
        Aabb box;
        for (const Vec3f& p : cloud.points) {
            if (is_finite(p)) box.add(p.cast<double>());
        }
        EXPECT_LT((box.size() - c.extent).cwiseAbs().maxCoeff(), 0.051) << box.size().transpose();
    }
}

}  // namespace
}  // namespace surfgrow::test
