// Fusing filtered scans from several poses into one labelled cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/range_filter.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace {

using namespace surfgrow::scanner;
using surfgrow::Error;
using surfgrow::ErrorCode;
using surfgrow::PointCloud;
using surfgrow::Vec3d;

// Distance of p from a face's surface (plane, or cylinder side).
double distance_to_face(const Face& f, const Vec3d& p) {
    if (f.planar()) return std::abs(f.plane().signed_distance(p));
    const Vec3d w = p - f.center;
    return std::abs((w - w.dot(f.normal) * f.normal).norm() - f.half_u_m);
}

class FuseIBeam : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        desc_ = new SceneDescription(ibeam_channel_scene());
        scene_ = new Scene(*desc_);
        poses_ = new std::vector<Pose>(scan_poses(desc_->scanner, 3));
        raws_ = new std::vector<RawScan>();
        for (SimulatedScan& s : ScanSimulator(*scene_).simulate(*poses_, 1))
            raws_->push_back(std::move(s.raw));
        cloud_ = new PointCloud(fuse_scans(*raws_));
    }
    static void TearDownTestSuite() {
        delete cloud_;
        delete raws_;
        delete poses_;
        delete scene_;
        delete desc_;
    }
    static SceneDescription* desc_;
    static Scene* scene_;
    static std::vector<Pose>* poses_;
    static std::vector<RawScan>* raws_;
    static PointCloud* cloud_;
};
SceneDescription* FuseIBeam::desc_ = nullptr;
Scene* FuseIBeam::scene_ = nullptr;
std::vector<Pose>* FuseIBeam::poses_ = nullptr;
std::vector<RawScan>* FuseIBeam::raws_ = nullptr;
PointCloud* FuseIBeam::cloud_ = nullptr;

TEST_F(FuseIBeam, ScanIndexAndOriginsAreConsistent) {
    const PointCloud& c = *cloud_;
    ASSERT_GT(c.size(), 300000u);
    ASSERT_TRUE(c.has_scan_index());
    ASSERT_EQ(c.scan_origins.size(), 3u);
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(c.scan_origins[static_cast<std::size_t>(k)],
                  (*poses_)[static_cast<std::size_t>(k)].translation());
    EXPECT_FALSE(c.viewpoint.has_value());
    // Points come scan by scan, each scan as many as its rays with a filtered range.
    std::vector<std::size_t> per_scan(3, 0);
    for (std::size_t i = 0; i < c.size(); ++i) {
        ASSERT_LT(c.scan_index[i], 3u);
        if (i > 0) {
            ASSERT_GE(c.scan_index[i], c.scan_index[i - 1]);
        }
        ++per_scan[c.scan_index[i]];
    }
    for (std::size_t k = 0; k < 3; ++k) {
        const RawScan& r = (*raws_)[k];
        const RangeFilter f(r.spec.readings_per_ray, 1, r.spec.laser.min_range_mm,
                            r.spec.laser.max_range_mm);
        std::size_t expected = 0;
        for (std::size_t ray = 0; ray < r.spec.rays(); ++ray)
            expected += std::isnan(f(r.ray_readings(ray))) ? 0 : 1;
        EXPECT_EQ(per_scan[k], expected);
        EXPECT_GT(per_scan[k], 100000u);
    }
    // Every point is within the sensor's range of its own scan's origin (4 m + the offset).
    for (std::size_t i = 0; i < c.size(); i += 97)
        EXPECT_LT((c.points[i].cast<double>() - c.scan_origins[c.scan_index[i]]).norm(), 4.05);
}

TEST_F(FuseIBeam, LabelledPointsLieWithinNoiseOfTheirTrueFace) {
    const PointCloud& c = *cloud_;
    ASSERT_TRUE(c.has_labels());
    const NoiseModel noise;
    std::size_t labelled = 0, beyond_3sigma = 0;
    std::vector<int> faces_seen(scene_->faces().size(), 0);
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (c.labels[i] < 0) continue;
        ++labelled;
        const Vec3d p = c.points[i].cast<double>();
        const Face& f = scene_->faces()[static_cast<std::size_t>(c.labels[i])];
        ++faces_seen[static_cast<std::size_t>(f.id)];
        const double range_mm = 1000.0 * (p - c.scan_origins[c.scan_index[i]]).norm();
        const double sigma_m = noise.sigma_mm(range_mm) * 1e-3;  // of a single reading
        const double d = distance_to_face(f, p);
        ASSERT_LT(d, 6 * sigma_m + 1e-3) << "point " << i << " on face " << f.id;
        beyond_3sigma += d > 3 * sigma_m ? 1 : 0;
    }
    EXPECT_GT(labelled, c.size() * 9 / 10);
    EXPECT_LT(beyond_3sigma, labelled / 100);
    // The paper's structure is seen: deck, both webs, flanges, stiffeners and bolt heads.
    auto seen = [&](const std::string& name) {
        int n = 0;
        for (const Face& f : scene_->faces())
            if (desc_->primitives[static_cast<std::size_t>(f.primitive)].name == name)
                n += faces_seen[static_cast<std::size_t>(f.id)];
        return n;
    };
    for (const char* name :
         {"deck", "left-web", "right-web", "left-bottom-flange", "right-top-flange",
          "left-stiffener-1", "right-web-splice", "left-bolt-5"})
        EXPECT_GT(seen(name), 20) << name;
}

TEST(Fuse, KnownWallFromTwoPosesLandsOnTheWall) {
    SceneDescription d;
    d.primitives.push_back(
        {"wall", Rectangle{Vec3d(1.2, 0, 0), Vec3d::UnitZ(), Vec3d::UnitY(), 10, 10}});
    const Scene scene(d);
    const ScanSimulator sim(scene, ScannerSpec{}, NoiseModel::ideal());
    const std::vector<Pose> poses = {pose_from_xyz_rpy(Vec3d(0, 0, 0), Vec3d::Zero()),
                                     pose_from_xyz_rpy(Vec3d(0.2, 0.5, 0.1), Vec3d(0, 0, 0.3))};
    std::vector<RawScan> raws;
    for (SimulatedScan& s : sim.simulate(poses, 1)) raws.push_back(std::move(s.raw));
    const PointCloud c = fuse_scans(raws);
    ASSERT_GT(c.size(), 10000u);
    for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_NEAR(c.points[i].x(), 1.2, 6e-4);  // 1 mm quantisation, eq. (1) averages
        EXPECT_EQ(c.labels[i], 0);
    }
    EXPECT_EQ(c.scan_origins[1], Vec3d(0.2, 0.5, 0.1));
}

TEST(Fuse, SingleScanSetsTheViewpointAndNoTruthMeansNoLabels) {
    SceneDescription d;
    d.primitives.push_back(
        {"wall", Rectangle{Vec3d(1, 0, 0), Vec3d::UnitZ(), Vec3d::UnitY(), 10, 10}});
    const Scene scene(d);
    RawScan raw =
        ScanSimulator(scene).simulate(pose_from_xyz_rpy(Vec3d(0, 0, 0.5), Vec3d::Zero()), 1).raw;
    raw.truth_face_id.clear();
    const PointCloud c = fuse_scans(std::vector<RawScan>{raw});
    ASSERT_TRUE(c.viewpoint.has_value());
    EXPECT_EQ(*c.viewpoint, Vec3d(0, 0, 0.5));
    EXPECT_FALSE(c.has_labels());
    EXPECT_TRUE(fuse_scans({}).empty());
}

TEST(Fuse, BadParametersAreInvalidParameterErrors) {
    RawScan raw;  // an all-zero scan of the default spec
    raw.readings_mm.assign(raw.spec.readings(), 0);
    const std::vector<RawScan> scans{raw};
    auto code_of = [&](FuseOptions o) {
        try {
            (void)fuse_scans(scans, o);
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("scan 0"), std::string::npos) << e.what();
            return e.code();
        }
        return ErrorCode::kInternal;
    };
    FuseOptions o;
    o.trim_q = 3;  // n = 5 <= 2q
    EXPECT_EQ(code_of(o), ErrorCode::kInvalidParameter);
    o = FuseOptions{};
    o.max_range_mm = 5600;  // beyond the sensor's 4000 mm
    EXPECT_EQ(code_of(o), ErrorCode::kInvalidParameter);
    o = FuseOptions{};
    o.min_range_mm = 10;  // below its 20 mm
    EXPECT_EQ(code_of(o), ErrorCode::kInvalidParameter);
    o = FuseOptions{};
    o.min_range_mm = 3000;
    o.max_range_mm = 2000;
    EXPECT_EQ(code_of(o), ErrorCode::kInvalidParameter);
    o = FuseOptions{};
    o.min_range_mm = 500;
    o.max_range_mm = 1500;
    EXPECT_EQ(fuse_scans(scans, o).size(), 0u);  // valid limits: no error
    RawScan short_scan = raw;
    short_scan.readings_mm.pop_back();
    EXPECT_THROW((void)fuse_scans(std::vector<RawScan>{short_scan}), Error);
    RawScan skewed = raw;
    skewed.pose.linear() *= 1.5;
    EXPECT_THROW((void)fuse_scans(std::vector<RawScan>{skewed}), Error);
}

}  // namespace
