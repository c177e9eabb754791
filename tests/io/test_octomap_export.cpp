// environment.bt: loads back in liboctomap with the grid's occupied cells, and free space carved
// between the scanner and the walls of a simulated room-corner scan.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <set>
#include <sstream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/io/octomap_export.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"
#include "surfgrow/robot/sensor_origins.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace surfgrow {
namespace {

using KeyTuple = std::tuple<int, int, int>;

// Every full-depth leaf of a state, pruned leaves expanded, as key tuples.
std::set<KeyTuple> leaves(const octomap::OcTree& tree, bool occupied) {
    std::set<KeyTuple> out;
    const unsigned depth = tree.getTreeDepth();
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        if (tree.isNodeOccupied(*it) != occupied) continue;
        const int span = 1 << (depth - it.getDepth());
        // A pruned leaf's key is its centre's key; its full-depth cells start span/2 below.
        const octomap::OcTreeKey k = it.getKey();
        const int base[3] = {k[0] - span / 2 * (span > 1), k[1] - span / 2 * (span > 1),
                             k[2] - span / 2 * (span > 1)};
        for (int x = 0; x < span; ++x)
            for (int y = 0; y < span; ++y)
                for (int z = 0; z < span; ++z) out.insert({base[0] + x, base[1] + y, base[2] + z});
    }
    return out;
}

octomap::OcTree load(const std::string& bytes) {
    octomap::OcTree tree(0.1);
    std::istringstream in(bytes);
    EXPECT_TRUE(tree.readBinary(in));
    return tree;
}

// One simulated scan of the room corner, grown: the cloud carries its scan origin.
struct RoomCorner {
    PointCloud cloud;
    GrowerConfig config;
    GrowResult result;
    OccupancyGrid grid;
    Vec3d origin;
};

const RoomCorner& room_corner() {
    static const RoomCorner rc = [] {
        RoomCorner r;
        const scanner::Scene scene(scanner::room_corner_scene());
        scanner::ScannerSpec spec;
        spec.tilt.step_deg = 2.0 / 3.0;  // half the paper's rows: fast, still dense at 1 m
        spec.tilt.positions = 180;
        const scanner::Pose pose = scene.description().scanner.home;
        std::vector<scanner::RawScan> raws{
            scanner::ScanSimulator(scene, spec).simulate(pose, 1).raw};
        r.cloud = scanner::fuse_scans(raws);
        r.origin = pose.translation();
        r.config.mu = 0.02;
        r.result = grow_surfaces(r.cloud, r.config);
        r.grid = occupancy_grid(r.cloud, r.result, r.config);
        return r;
    }();
    return rc;
}

std::string export_bt(const RoomCorner& rc, const SensorOrigins& origins,
                      io::OctomapSummary* summary = nullptr) {
    std::ostringstream out;
    const io::OctomapSummary s = io::write_octomap_bt(
        out, rc.grid, rc.cloud, grown_point_mask(rc.cloud, rc.config), origins, rc.config.threads);
    if (summary) *summary = s;
    return out.str();
}

TEST(OctomapExport, LoadsBackWithTheGridsOccupiedCells) {
    const RoomCorner& rc = room_corner();
    ASSERT_GT(rc.grid.size(), 1000u);
    ASSERT_EQ(rc.cloud.scan_origins.size(), 1u);
    io::OctomapSummary summary;
    const std::string bytes = export_bt(rc, sensor_origins(rc.cloud, rc.config), &summary);
    const octomap::OcTree tree = load(bytes);
    EXPECT_DOUBLE_EQ(tree.getResolution(), rc.config.mu);

    // Expected: the leaf holding each occupied cube's centre. Compared as cell centres.
    std::set<KeyTuple> expected;
    for (const CellCoords& c : rc.grid.cells()) {
        const Vec3d p = rc.grid.centre(c);
        const octomap::OcTreeKey k = tree.coordToKey(p.x(), p.y(), p.z());
        expected.insert({k[0], k[1], k[2]});
        // That leaf's centre lies within half a leaf of the cube's centre on each axis.
        const octomap::point3d leaf = tree.keyToCoord(k);
        for (int a = 0; a < 3; ++a)
            EXPECT_LE(std::abs(double(leaf(a)) - p[a]), 0.5 * rc.config.mu + 1e-6);
    }
    const std::set<KeyTuple> occupied = leaves(tree, true);
    EXPECT_EQ(occupied.size(), rc.grid.size());
    EXPECT_EQ(occupied, expected);
    EXPECT_EQ(summary.occupied, rc.grid.size());
    EXPECT_EQ(summary.free, leaves(tree, false).size());
    EXPECT_GT(summary.free, 10 * summary.occupied);  // a room is mostly air
    EXPECT_EQ(summary.carving, SensorOrigins::Source::kScanOrigins);
}

TEST(OctomapExport, FreeBetweenScannerAndWallsUnknownBehindThem) {
    const RoomCorner& rc = room_corner();
    const octomap::OcTree tree = load(export_bt(rc, sensor_origins(rc.cloud, rc.config)));
    const double mu = rc.config.mu;
    // Points on the walls (x = 1.5, y = 1.5) and the floor (z = 0), in the scanner's view.
    const Vec3d targets[] = {{1.5, 1.0, 0.8}, {1.5, 1.3, 0.3}, {1.0, 1.5, 0.9},
                             {1.2, 1.5, 0.5}, {1.0, 1.0, 0.0}, {0.8, 1.0, 0.0}};
    int free_checked = 0;
    for (const Vec3d& target : targets) {
        const Vec3d dir = (target - rc.origin).normalized();
        const double length = (target - rc.origin).norm();
        // Free from the scanner to 3 cells before the wall.
        for (double t = 0.0; t < length - 3 * mu; t += 0.5 * mu) {
            const Vec3d p = rc.origin + t * dir;
            const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
            ASSERT_NE(node, nullptr)
                << "unknown at " << p.transpose() << " toward " << target.transpose();
            ASSERT_FALSE(tree.isNodeOccupied(node)) << "occupied at " << p.transpose();
            ++free_checked;
        }
        // The wall itself is occupied within a cell of the target.
        bool wall = false;
        for (double t = -1.5 * mu; t <= 1.5 * mu; t += 0.25 * mu) {
            const Vec3d p = target + t * dir;
            const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
            wall = wall || (node && tree.isNodeOccupied(node));
        }
        EXPECT_TRUE(wall) << target.transpose();
        // Behind it nothing was seen: unknown.
        for (double t = 3 * mu; t < 0.3; t += mu) {
            const Vec3d p = target + t * dir;
            EXPECT_EQ(tree.search(p.x(), p.y(), p.z()), nullptr)
                << "known behind the wall at " << p.transpose();
        }
    }
    EXPECT_GT(free_checked, 500);
    // Behind the scanner, outside the scan's field of view: unknown.
    const Vec3d behind = rc.origin - Vec3d(0.4, 0.4, 0);
    EXPECT_EQ(tree.search(behind.x(), behind.y(), behind.z()), nullptr);
}

TEST(OctomapExport, FreeLeavesAreExactlyOctomapsRaysLessTheOccupiedAndEndLeaves) {
    // The contract, computed with liboctomap itself: the union of computeRayKeys from the scan
    // origin to the centre of each grown point's leaf, less the occupied leaves and the end
    // leaves. surfgrow walks the rays itself; this holds it to OctoMap's leaves.
    const RoomCorner& rc = room_corner();
    const octomap::OcTree tree = load(export_bt(rc, sensor_origins(rc.cloud, rc.config)));
    const std::vector<std::uint8_t> mask = grown_point_mask(rc.cloud, rc.config);
    const octomap::point3d from(static_cast<float>(rc.origin.x()),
                                static_cast<float>(rc.origin.y()),
                                static_cast<float>(rc.origin.z()));
    std::set<KeyTuple> ends, crossed;
    octomap::KeyRay ray;
    for (std::size_t i = 0; i < rc.cloud.size(); ++i) {
        if (!mask.empty() && !mask[i]) continue;
        const Vec3f& p = rc.cloud.points[i];
        const octomap::OcTreeKey end = tree.coordToKey(p.x(), p.y(), p.z());
        if (!ends.insert({end[0], end[1], end[2]}).second) continue;
        ASSERT_TRUE(tree.computeRayKeys(from, tree.keyToCoord(end), ray));
        for (const octomap::OcTreeKey& k : ray) crossed.insert({k[0], k[1], k[2]});
    }
    const std::set<KeyTuple> occupied = leaves(tree, true);
    std::set<KeyTuple> expected;
    for (const KeyTuple& k : crossed)
        if (!occupied.count(k) && !ends.count(k)) expected.insert(k);
    ASSERT_GT(expected.size(), 10000u);
    EXPECT_EQ(leaves(tree, false), expected);
}

TEST(OctomapExport, ABoxTooLargeForABitmapGivesTheSameLeavesFromSortedKeys) {
    // Three strays 30 m away stretch the rays' box to about 1500^3 leaves, beyond the bitmap's
    // 2^29: the free leaves are then kept as sorted keys, and must still be OctoMap's rays less
    // the occupied and end leaves. Every finite point casts a ray (no mask).
    const RoomCorner& rc = room_corner();
    PointCloud cloud = rc.cloud;
    const Vec3f o = rc.origin.cast<float>();
    for (const Vec3f& d : {Vec3f(30, 0, 0), Vec3f(0, 30, 0), Vec3f(0, 0, 30)})
        cloud.points.push_back(o + d);
    if (!cloud.scan_index.empty()) cloud.scan_index.resize(cloud.points.size(), 0u);
    SensorOrigins one;
    one.source = SensorOrigins::Source::kViewpoint;
    one.origins = {rc.origin};
    std::ostringstream out;
    (void)io::write_octomap_bt(out, rc.grid, cloud, {}, one, 2);
    const octomap::OcTree tree = load(out.str());
    const octomap::point3d from(o.x(), o.y(), o.z());
    std::set<KeyTuple> ends, crossed;
    octomap::KeyRay ray;
    for (const Vec3f& p : cloud.points) {
        const octomap::OcTreeKey end = tree.coordToKey(p.x(), p.y(), p.z());
        if (!ends.insert({end[0], end[1], end[2]}).second) continue;
        ASSERT_TRUE(tree.computeRayKeys(from, tree.keyToCoord(end), ray));
        for (const octomap::OcTreeKey& k : ray) crossed.insert({k[0], k[1], k[2]});
    }
    const std::set<KeyTuple> occupied = leaves(tree, true);
    EXPECT_EQ(occupied.size(), rc.grid.size());
    std::set<KeyTuple> expected;
    for (const KeyTuple& k : crossed)
        if (!occupied.count(k) && !ends.count(k)) expected.insert(k);
    ASSERT_GT(expected.size(), 10000u);
    EXPECT_EQ(leaves(tree, false), expected);
}

TEST(OctomapExport, WithoutOriginsOnlyOccupiedCells) {
    const RoomCorner& rc = room_corner();
    io::OctomapSummary summary;
    const octomap::OcTree tree = load(export_bt(rc, SensorOrigins{}, &summary));
    EXPECT_EQ(summary.free, 0u);
    EXPECT_EQ(summary.rays, 0u);
    EXPECT_EQ(leaves(tree, false).size(), 0u);
    EXPECT_EQ(leaves(tree, true).size(), rc.grid.size());
    // One viewpoint for every point: the same as the scan origin here.
    SensorOrigins one;
    one.source = SensorOrigins::Source::kViewpoint;
    one.origins = {rc.origin};
    EXPECT_EQ(export_bt(rc, one), export_bt(rc, sensor_origins(rc.cloud, rc.config)));
}

TEST(OctomapExport, SameBytesEveryTimeAndForAnyThreadCount) {
    const RoomCorner& rc = room_corner();
    const std::string a = export_bt(rc, sensor_origins(rc.cloud, rc.config));
    EXPECT_EQ(export_bt(rc, sensor_origins(rc.cloud, rc.config)), a);
    GrowerConfig one = rc.config;
    one.threads = 1;
    RoomCorner copy = rc;
    copy.config = one;
    copy.result = grow_surfaces(rc.cloud, one);
    copy.grid = occupancy_grid(rc.cloud, copy.result, one);
    EXPECT_EQ(export_bt(copy, sensor_origins(rc.cloud, one)), a);
}

TEST(OctomapExport, EmptyGridGivesAnEmptyMap) {
    PointCloud cloud;
    GrowerConfig config;
    const OccupancyGrid grid = occupancy_grid(cloud, std::vector<std::int32_t>{}, config);
    std::ostringstream out;
    const io::OctomapSummary s = io::write_octomap_bt(out, grid, cloud, {}, SensorOrigins{});
    EXPECT_EQ(s.occupied, 0u);
    const octomap::OcTree tree = load(out.str());
    EXPECT_EQ(tree.size(), 0u);
    EXPECT_DOUBLE_EQ(tree.getResolution(), config.mu);
    // The resolution is written at full precision: 1/300 reads back exactly.
    std::ostringstream third;
    (void)io::write_octomap_bt(third, OccupancyGrid(1.0 / 300), cloud, {}, SensorOrigins{});
    EXPECT_EQ(load(third.str()).getResolution(), 1.0 / 300);
}

TEST(OctomapExport, CellsBeyondOctomapsRangeAreAClearError) {
    // 500 m from the frame origin at 12 mm: beyond 32768 cells.
    PointCloud cloud;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j)
            cloud.points.push_back({500.0f + 0.004f * float(i), 0.004f * float(j), 0.0f});
    GrowerConfig config;
    const GrowResult r = grow_surfaces(cloud, config);
    const OccupancyGrid grid = occupancy_grid(cloud, r, config);
    ASSERT_FALSE(grid.empty());
    std::ostringstream out;
    try {
        (void)io::write_octomap_bt(out, grid, cloud, {}, SensorOrigins{});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
        EXPECT_NE(std::string(e.what()).find("environment.bt"), std::string::npos);
        // What to do about it: a georeferenced survey can still be grown without the OctoMap.
        EXPECT_NE(std::string(e.what()).find("--no-octomap"), std::string::npos) << e.what();
    }
}

TEST(OctomapExport, ARayEndBeyondTheRangeNamesTheFirstSuchPoint) {
    // The room corner's points with two far strays appended (not registered, so not in the
    // grid): the rays are collected in parallel chunks, and the error still names the first.
    const RoomCorner& rc = room_corner();
    ASSERT_GT(rc.cloud.size(), 65536u);  // enough for parallel chunks
    PointCloud cloud = rc.cloud;
    cloud.points.insert(cloud.points.begin() + 1000, Vec3f(0.5f, 0.25f, 900.0f));
    cloud.points.push_back({0.5f, -700.0f, 0.25f});
    if (!cloud.scan_index.empty()) {
        cloud.scan_index.insert(cloud.scan_index.begin() + 1000, 0u);
        cloud.scan_index.push_back(0u);
    }
    SensorOrigins one;
    one.source = SensorOrigins::Source::kViewpoint;
    one.origins = {rc.origin};
    for (const int threads : {1, 2}) {
        std::ostringstream out;
        try {
            (void)io::write_octomap_bt(out, rc.grid, cloud, {}, one, threads);
            FAIL() << "no error";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
            const std::string what = e.what();
            EXPECT_NE(what.find("a point"), std::string::npos) << what;
            EXPECT_NE(what.find("900"), std::string::npos) << what;
            EXPECT_EQ(what.find("-700"), std::string::npos) << what;
        }
    }
}

}  // namespace
}  // namespace surfgrow

namespace surfgrow {
namespace {

// The room corner's points as scans appended one by one, each from its own origin: the second
// from 2 m away (its rays reach past the first box: the bits move to a larger one), the third
// back inside, the fourth with a stray 40 m off (a box too large for a bitmap: sorted keys).
struct GrowingScans {
    std::vector<PointCloud> clouds;  // scans 0..k
    std::vector<SensorOrigins> origins;
};

GrowingScans growing_scans() {
    const RoomCorner& rc = room_corner();
    const std::vector<Vec3d> from = {rc.origin, rc.origin + Vec3d(2.0, 0.5, 0.0),
                                     rc.origin + Vec3d(-0.3, 0.2, 0.1), rc.origin};
    GrowingScans g;
    PointCloud cloud;
    const std::size_t n = rc.cloud.size();
    for (std::size_t k = 0; k < from.size(); ++k) {
        for (std::size_t i = k * n / 4; i < (k + 1) * n / 4; ++i) {
            cloud.points.push_back(rc.cloud.points[i]);
            cloud.scan_index.push_back(static_cast<std::uint32_t>(k));
        }
        if (k == 3) {
            cloud.points.push_back(rc.origin.cast<float>() + Vec3f(40, 0, 0));
            cloud.scan_index.push_back(3u);
        }
        cloud.scan_origins.push_back(from[k]);
        g.clouds.push_back(cloud);
        SensorOrigins o;
        o.source = SensorOrigins::Source::kScanOrigins;
        o.origins = cloud.scan_origins;
        g.origins.push_back(o);
    }
    return g;
}

// Whether the carver's next write gives the bytes of write_octomap_bt on the whole cloud.
bool writes_the_whole_clouds_bytes(io::OctomapCarver& carver, const OccupancyGrid& grid,
                                   const PointCloud& cloud, const SensorOrigins& origins) {
    std::ostringstream step, whole;
    (void)carver.write(step, grid, cloud, {}, origins, 2);
    (void)io::write_octomap_bt(whole, grid, cloud, {}, origins, 2);
    return step.str() == whole.str();
}

// A carver that has written scans 0..k.
io::OctomapCarver carver_through(const GrowingScans& g, std::size_t k) {
    io::OctomapCarver carver;
    std::ostringstream ignored;
    (void)carver.write(ignored, room_corner().grid, g.clouds[k], {}, g.origins[k], 2);
    return carver;
}

}  // namespace

TEST(OctomapCarver, ScanByScanWritesWhatTheWholeCloudWouldGive) {
    const RoomCorner& rc = room_corner();
    const GrowingScans g = growing_scans();
    for (const int threads : {1, 2}) {
        io::OctomapCarver carver;
        for (std::size_t k = 0; k < g.clouds.size(); ++k) {
            std::ostringstream step, whole;
            const io::OctomapSummary s =
                carver.write(step, rc.grid, g.clouds[k], {}, g.origins[k], threads);
            const io::OctomapSummary w =
                io::write_octomap_bt(whole, rc.grid, g.clouds[k], {}, g.origins[k], threads);
            ASSERT_GT(w.free, 1000u);
            EXPECT_EQ(s.free, w.free) << "scan " << k;
            EXPECT_EQ(s.rays, w.rays) << "scan " << k;
            EXPECT_TRUE(step.str() == whole.str()) << "scan " << k << ", " << threads << " threads";
        }
    }
}

TEST(OctomapCarver, ACloudThatDidNotOnlyGrowStartsAfresh) {
    const RoomCorner& rc = room_corner();
    const GrowingScans g = growing_scans();
    io::OctomapCarver carver = carver_through(g, 2);
    // Fewer points (an earlier map), then other origins (another job): each as from scratch.
    for (const auto& [cloud, origins] :
         {std::pair{g.clouds[1], g.origins[1]}, std::pair{g.clouds[2], SensorOrigins{}}})
        EXPECT_TRUE(writes_the_whole_clouds_bytes(carver, rc.grid, cloud, origins));
    // Another resolution: its own rays.
    const OccupancyGrid coarse = occupancy_grid(rc.cloud, rc.result, [&] {
        GrowerConfig c = rc.config;
        c.mu = 0.05;
        return c;
    }());
    EXPECT_TRUE(writes_the_whole_clouds_bytes(carver, coarse, g.clouds[2], g.origins[2]));
}

// A scan with a point beyond OctoMap's range is refused whole: the carver still holds the scans
// before it, and the next good scan gives the whole cloud's bytes.
TEST(OctomapCarver, AScanThatFailsLeavesWhatWasCarvedBefore) {
    const RoomCorner& rc = room_corner();
    const GrowingScans g = growing_scans();
    io::OctomapCarver carver = carver_through(g, 1);
    std::ostringstream ignored;
    PointCloud bad = g.clouds[2];
    bad.points.push_back({0.5f, 0.25f, 900.0f});
    bad.scan_index.push_back(2u);
    EXPECT_THROW((void)carver.write(ignored, rc.grid, bad, {}, g.origins[2], 2), Error);
    EXPECT_TRUE(writes_the_whole_clouds_bytes(carver, rc.grid, g.clouds[2], g.origins[2]));
}

}  // namespace surfgrow
