// Bound planes on analytic scenes: exact normals, holes, concave outlines, bad input.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <functional>
#include <random>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/planes/plane_mesh.hpp"

namespace surfgrow {
namespace {

using test::Rect;

constexpr double kDeg = M_PI / 180.0;

struct Grown {
    PointCloud cloud;
    GrowResult result;
};

// Samples the rectangles (5 mm grid, noise sigma), drops points where `cut` says, grows.
Grown grow_rects(const std::vector<Rect>& rects, double sigma,
                 const std::function<bool(const Vec3d&)>& cut = {}, std::uint64_t seed = 1) {
    Grown g;
    std::mt19937_64 rng(seed);
    std::vector<Vec3f> pts;
    for (const Rect& r : rects) test::sample_rect(r, 0.005, 0.3, sigma, rng, pts);
    for (const Vec3f& p : pts)
        if (!cut || !cut(p.cast<double>())) g.cloud.points.push_back(p);
    // In front of every face used here (the floor, the wall at x = 0, plates at z = 0.5): a
    // sensor in a plate's own plane would see it edge-on, where the disk test rightly finds none.
    g.cloud.viewpoint = Vec3d(0.3, 0.4, 1.0);
    g.result = grow_surfaces(g.cloud, GrowerConfig{});
    return g;
}

BoundPlanes planes_of(const Grown& g, BoundPlaneConfig cfg = {}) {
    return compute_bound_planes(g.cloud, g.result, cfg);
}

// Planes holding at least 2 % of the points: the faces, without edge slivers.
std::vector<const BoundPlane*> major(const BoundPlanes& p) {
    std::vector<const BoundPlane*> out;
    for (const BoundPlane& bp : p.planes)
        if (double(bp.point_count) >= 0.02 * double(p.stats.points)) out.push_back(&bp);
    return out;
}

const Rect kFloor{{0.2, 0.15, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15};
const Rect kWall{{0, 0.15, 0.15}, Vec3d::UnitY(), Vec3d::UnitZ(), 0.15, 0.15};

TEST(BoundPlanes, AnLOfTwoPlanesGivesTwoRegionsWithExactNormals) {
    const Grown g = grow_rects({kFloor, kWall}, 0.0);
    const BoundPlanes p = planes_of(g);
    const auto faces = major(p);
    ASSERT_EQ(faces.size(), 2u);
    // The floor has more points, so it comes first; normals face the viewpoint.
    EXPECT_LT(angle_between(faces[0]->normal, Vec3d::UnitZ()), 1e-3);
    EXPECT_LT(angle_between(faces[1]->normal, Vec3d::UnitX()), 1e-3);
    EXPECT_NEAR(faces[0]->centroid.z(), 0.0, 1e-4);
    EXPECT_NEAR(faces[1]->centroid.x(), 0.0, 1e-4);
    EXPECT_NEAR(faces[0]->area, 0.4 * 0.3, 0.05 * 0.12);
    EXPECT_NEAR(faces[1]->area, 0.3 * 0.3, 0.05 * 0.09);
    EXPECT_LT(faces[0]->rms, 5e-4);  // noise-free; what there is comes from edge points
    // Nearly every point is in one of the two faces.
    EXPECT_GE(double(faces[0]->point_count + faces[1]->point_count), 0.97 * double(p.stats.points));
    EXPECT_EQ(p.stats.patches, g.result.surfaces.size());
    EXPECT_EQ(p.stats.patches_merged, g.result.surfaces.size());
}

TEST(BoundPlanes, NoisyLKeepsNormalsWithinATenthOfADegree) {
    const Grown g = grow_rects({kFloor, kWall}, 0.0015);
    const BoundPlanes p = planes_of(g);
    const auto faces = major(p);
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_LT(angle_between(faces[0]->normal, Vec3d::UnitZ()), 0.1 * kDeg);
    EXPECT_LT(angle_between(faces[1]->normal, Vec3d::UnitX()), 0.1 * kDeg);
    EXPECT_NEAR(faces[0]->rms, 0.0015, 0.0004);
    // The offset default comes from the measured noise: 3 sigma, within [mu/4, mu/2].
    EXPECT_NEAR(p.config.max_offset, 3 * p.stats.noise, 1e-12);
    EXPECT_GT(p.stats.noise, 0.0008);
}

TEST(BoundPlanes, AStripOfTheNeighbouringFaceDoesNotTiltThePlane) {
    // A floor patch (noise 1 mm) that took in the wall's points within its tolerance along their
    // edge, as registration does along every edge (a hand-made result, to control the strip): the
    // least-squares plane of all members tilts by half a degree; the face's plane is fitted on
    // the members within 3 robust sigma, which the strip (4 mm and more above) is not.
    PointCloud c;
    GrowResult r;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 0.001);
    for (int i = 0; i <= 60; ++i)
        for (int j = 0; j <= 40; ++j)
            c.points.emplace_back(float(0.005 * i), float(0.005 * j), float(noise(rng)));
    for (int k = 2; k <= 6; ++k)  // the wall x = 0.3, from 4 to 12 mm above the floor
        for (int j = 0; j <= 40; ++j)
            c.points.emplace_back(float(0.3 + noise(rng)), float(0.005 * j), float(0.002 * k));
    r.labels.assign(c.points.size(), 0);
    Surface surf;
    surf.home = Vec3d(0.15, 0.1, 0);
    surf.centroid = surf.home;
    surf.normal = Vec3d::UnitZ();
    surf.eigenvalues = Vec3d(1e-6, 1e-3, 1e-2);
    surf.radius = 0.012;
    surf.neighbours = 20;
    surf.point_count = c.points.size();
    r.surfaces.push_back(surf);
    c.viewpoint = Vec3d(0.15, 0.1, 1);

    // The plain least-squares normal, for contrast.
    Vec3d mean = Vec3d::Zero();
    for (const Vec3f& p : c.points) mean += p.cast<double>();
    mean /= double(c.points.size());
    Mat3d cov = Mat3d::Zero();
    for (const Vec3f& p : c.points)
        cov += (p.cast<double>() - mean) * (p.cast<double>() - mean).transpose();
    const Vec3d plain = Eigen::SelfAdjointEigenSolver<Mat3d>(cov).eigenvectors().col(0);
    EXPECT_GT(angle_between(plain, Vec3d::UnitZ()), 0.3 * kDeg);

    const BoundPlanes p = compute_bound_planes(c, r, BoundPlaneConfig{});
    ASSERT_EQ(p.planes.size(), 1u);
    const BoundPlane& bp = p.planes[0];
    EXPECT_LT(angle_between(bp.normal, Vec3d::UnitZ()), 0.05 * kDeg);
    EXPECT_NEAR(bp.centroid.z(), 0.0, 3e-4);     // the inliers' centroid, on the floor
    EXPECT_EQ(bp.point_count, c.points.size());  // every member stays in the face
    EXPECT_GT(bp.rms, 0.002);                    // which the strip's distances show
}

TEST(BoundPlanes, APlateWithASquareHoleHasOneHoleOfTheRightArea) {
    const Rect plate{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15};
    const Grown g = grow_rects({plate}, 0.0005, [](const Vec3d& p) {
        return std::abs(p.x() - 0.05) < 0.05 && std::abs(p.y()) < 0.05;  // 100 mm square
    });
    const BoundPlanes p = planes_of(g);
    ASSERT_EQ(p.planes.size(), 1u);
    const BoundPlane& bp = p.planes[0];
    ASSERT_EQ(bp.polygons.size(), 1u);
    ASSERT_EQ(bp.polygons[0].holes.size(), 1u);
    const double hole = std::abs(signed_area(bp.polygons[0].holes[0]));
    // The boundary runs half a raster cell outside the outermost points: the hole shrinks by
    // about a 3 mm strip on each side, the plate grows by the same.
    EXPECT_NEAR(hole, 0.1 * 0.1, 0.15 * 0.01);
    EXPECT_NEAR(bp.area, 0.4 * 0.3 - 0.01, 0.05 * 0.11);
    EXPECT_NEAR(bp.area, polygon_area(bp.polygons[0]), 1e-12);
    // The hole's centre is outside, the plate's corner region inside.
    EXPECT_FALSE(polygon_contains(bp.polygons[0], bp.to_plane({0.05, 0, 0.5})));
    EXPECT_TRUE(polygon_contains(bp.polygons[0], bp.to_plane({-0.15, -0.1, 0.5})));
}

TEST(BoundPlanes, AConcaveLPlateGivesAConcavePolygon) {
    const Rect plate{{0.2, 0.15, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15};
    const Grown g = grow_rects({plate}, 0.0005, [](const Vec3d& p) {
        return p.x() > 0.1 && p.y() > 0.1;  // leaves an L: 0.4 x 0.1 plus 0.1 x 0.2
    });
    const BoundPlanes p = planes_of(g);
    ASSERT_EQ(p.planes.size(), 1u);
    const BoundPlane& bp = p.planes[0];
    ASSERT_EQ(bp.polygons.size(), 1u);
    EXPECT_TRUE(bp.polygons[0].holes.empty());
    const Ring& ring = bp.polygons[0].outer;
    std::size_t reflex = 0;
    for (std::size_t i = 0; i < ring.size(); ++i)
        reflex += orient2d(ring[(i + ring.size() - 1) % ring.size()], ring[i],
                           ring[(i + 1) % ring.size()]) < 0;
    EXPECT_GE(reflex, 1u);
    EXPECT_FALSE(polygon_contains(bp.polygons[0], bp.to_plane({0.3, 0.2, 0.5})));  // the notch
    EXPECT_TRUE(polygon_contains(bp.polygons[0], bp.to_plane({0.3, 0.05, 0.5})));
    EXPECT_TRUE(polygon_contains(bp.polygons[0], bp.to_plane({0.05, 0.25, 0.5})));
    // The outline runs about half a point spacing outside the outermost points: 1.4 m of
    // perimeter x ~3 mm.
    EXPECT_NEAR(bp.area, 0.4 * 0.1 + 0.1 * 0.2 + 1.4 * 0.003, 0.002);
    // The mesh of the polygon has the same area.
    const PlaneMesh mesh = mesh_bound_planes(p);
    double area = 0;
    for (const auto& t : mesh.triangles) {
        const Vec3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
        const Vec3d n = (b - a).cross(c - a);
        EXPECT_GT(n.dot(bp.normal), 0);  // counter-clockwise seen from the normal
        area += 0.5 * n.norm();
    }
    EXPECT_NEAR(area, bp.area, 1e-9);
}

TEST(BoundPlanes, ParallelPlatesAStepApartStaySeparate) {
    // Two coplanar-looking plates 20 mm apart in height (a splice plate on a web).
    const Rect low{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15};
    const Rect high{{0.1, 0, 0.52}, Vec3d::UnitX(), Vec3d::UnitY(), 0.05, 0.05};
    const Grown g = grow_rects({low, high}, 0.0005, [](const Vec3d& p) {
        return p.z() < 0.51 && std::abs(p.x() - 0.1) < 0.05 && std::abs(p.y()) < 0.05;
    });
    const BoundPlanes planes = planes_of(g);  // alive while `faces` points into it
    const auto faces = major(planes);
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_NEAR(faces[0]->centroid.z(), 0.5, 1e-3);
    EXPECT_NEAR(faces[1]->centroid.z(), 0.52, 1e-3);
}

// Two horizontal pieces a step apart, then the same in one plane (`pieces(step)` grows them):
// apart, two planes, each within `max_angle` of flat and its own noise thin; together, one plane
// within `max_angle` of flat.
void expect_apart_at_a_step_one_without(const std::function<Grown(double)>& pieces, double step,
                                        const BoundPlaneConfig& cfg, double max_angle) {
    const Grown stepped = pieces(step);
    const BoundPlanes apart = planes_of(stepped, cfg);
    const auto two = major(apart);
    ASSERT_EQ(two.size(), 2u);
    for (const BoundPlane* bp : two) {
        EXPECT_LT(axis_angle_between(bp->normal, Vec3d::UnitZ()), max_angle);
        EXPECT_LT(bp->rms, 0.002);
    }
    const Grown flat = pieces(0.0);
    const BoundPlanes together = planes_of(flat, cfg);
    const auto one = major(together);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_LT(axis_angle_between(one[0]->normal, Vec3d::UnitZ()), max_angle);
}

TEST(BoundPlanes, ParallelStripsAStepApartAcrossAGapStaySeparate) {
    // A valve body's face and the pipe behind it: parallel, 30 mm apart, 40 mm between them
    // (within the gap bridging's reach). A plane tilted 5 degrees passes within the offset of
    // both centroids; it must not pass for one face. The same strips in one plane are one face. The
    // offset tolerance is that of a noisy scan (6 mm), which both centroids meet.
    auto strips = [](double step) {
        const Rect near{{0.075, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.075, 0.1};
        const Rect far{{0.34, 0, 0.5 + step}, Vec3d::UnitX(), Vec3d::UnitY(), 0.15, 0.1};
        return grow_rects({near, far}, 0.0005);
    };
    BoundPlaneConfig cfg;
    cfg.max_offset = 0.006;
    expect_apart_at_a_step_one_without(strips, 0.03, cfg, 0.5 * kDeg);
}

TEST(BoundPlanes, PlatesAStepApartSideBySideAreNotBridgedByALeaningPlane) {
    // A web and a splice plate 16 mm in front of it, side by side along x with 40 mm between
    // them (the channel's fused scans): regions short along the line between them, so the plane
    // through both centroids, leaning about 2 degrees, fits each within the offset (4.5 mm: a
    // fused scan's). Pooled pieces of one plane give a blend of their normals; this lean lies off
    // the arc between them. The same plates in one plane are one face.
    auto plates = [](double step) {
        const Rect plate{{0, 0, 0.5 + step}, Vec3d::UnitX(), Vec3d::UnitY(), 0.15, 0.2};
        const Rect web{{0.39, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.2};
        return grow_rects({plate, web}, 0.001);
    };
    BoundPlaneConfig cfg;
    cfg.max_offset = 0.0045;
    expect_apart_at_a_step_one_without(plates, 0.016, cfg, 0.3 * kDeg);
}

TEST(BoundPlanes, ACylinderIsCutIntoStripsNotOnePlane) {
    // 300 mm radius, quarter turn: pooled moments stop the region drifting round the curve.
    Grown g;
    for (double a = 0; a <= M_PI / 2; a += 0.005 / 0.3)
        for (double z = 0; z <= 0.3; z += 0.005)
            g.cloud.points.emplace_back(float(0.3 * std::cos(a)), float(0.3 * std::sin(a)),
                                        float(z));
    g.cloud.viewpoint = Vec3d(0, 0, 0.15);
    g.result = grow_surfaces(g.cloud, GrowerConfig{});
    const BoundPlanes p = planes_of(g);
    ASSERT_GE(p.planes.size(), 4u);
    for (const BoundPlane& bp : p.planes) EXPECT_LT(bp.rms, 0.006) << bp.patches.size();
}

TEST(BoundPlanes, SameBytesForAnyThreadCount) {
    const Grown g = grow_rects({kFloor, kWall}, 0.0015);
    BoundPlaneConfig cfg;
    cfg.threads = 1;
    const BoundPlanes a = planes_of(g, cfg);
    for (const int threads : {2, 5}) {
        cfg.threads = threads;
        const BoundPlanes b = planes_of(g, cfg);
        ASSERT_EQ(a.planes.size(), b.planes.size());
        EXPECT_EQ(a.plane_of_patch, b.plane_of_patch);
        for (std::size_t k = 0; k < a.planes.size(); ++k) {
            EXPECT_EQ(a.planes[k].normal, b.planes[k].normal);
            EXPECT_EQ(a.planes[k].centroid, b.planes[k].centroid);
            EXPECT_EQ(a.planes[k].area, b.planes[k].area);
            ASSERT_EQ(a.planes[k].polygons.size(), b.planes[k].polygons.size());
            for (std::size_t q = 0; q < a.planes[k].polygons.size(); ++q)
                EXPECT_EQ(a.planes[k].polygons[q].outer, b.planes[k].polygons[q].outer);
        }
    }
}

TEST(BoundPlanes, PlaneLabelsFollowThePatches) {
    const Grown g = grow_rects({kFloor, kWall}, 0.0);
    const BoundPlanes p = planes_of(g);
    const auto labels = plane_labels(p, g.result.labels);
    ASSERT_EQ(labels.size(), g.cloud.size());
    std::vector<std::uint64_t> count(p.planes.size(), 0);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (g.result.labels[i] < 0) {
            EXPECT_EQ(labels[i], -1);
            continue;
        }
        ASSERT_GE(labels[i], 0);
        ++count[std::size_t(labels[i])];
    }
    for (std::size_t k = 0; k < p.planes.size(); ++k) EXPECT_EQ(count[k], p.planes[k].point_count);
}

TEST(BoundPlanes, AGapIsBridgedFromTheLargerPatchOfAPair) {
    // A plate of 25 small patches (radius 12 mm) and, 30 mm away in its plane, one large patch
    // (radius 80 mm): a hand-made result. Their homes lie 18 mm beyond the sum of the radii, within
    // the 60 mm gap, yet farther from the small patch than 60 mm + 2 x 12 mm: only a search from
    // the large patch finds the pair.
    PointCloud c;
    std::vector<std::int32_t> labels;
    for (int i = 0; i <= 135; ++i)
        for (int j = 0; j <= 50; ++j) {
            const double x = 0.002 * i, y = 0.002 * j;
            if (x > 0.1 && x < 0.13) continue;
            c.points.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.f);
            labels.push_back(x <= 0.1 ? std::min(4, int(x / 0.02)) + 5 * std::min(4, int(y / 0.02))
                                      : 25);
        }
    std::vector<Surface> surfaces(26);
    std::vector<Vec3d> sum(26, Vec3d::Zero());
    std::vector<int> count(26, 0);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        sum[static_cast<std::size_t>(labels[i])] += c.points[i].cast<double>();
        ++count[static_cast<std::size_t>(labels[i])];
    }
    for (std::size_t s = 0; s < 26; ++s) {
        Surface& f = surfaces[s];
        f.centroid = sum[s] / count[s];
        f.home = s < 25 ? f.centroid : Vec3d(0.2, 0.05, 0);
        f.radius = s < 25 ? 0.012 : 0.08;
        f.eigenvalues = Vec3d(1e-8, 1e-4, 1e-4);
        f.point_count = static_cast<std::uint32_t>(count[s]);
    }
    ASSERT_GT((surfaces[25].home - surfaces[14].home).norm(), 0.06 + 2 * 0.012);
    BoundPlaneConfig cfg;  // mu 12 mm: the gap 60 mm, the adjacency 6 mm
    EXPECT_EQ(compute_bound_planes(c, surfaces, labels, cfg).planes.size(), 1u);
    cfg.max_gap = 0.015;  // below the 18 mm between them
    EXPECT_EQ(compute_bound_planes(c, surfaces, labels, cfg).planes.size(), 2u);
    cfg.max_gap = -1;  // never bridge
    EXPECT_EQ(compute_bound_planes(c, surfaces, labels, cfg).planes.size(), 2u);
}

TEST(BoundPlanes, EmptyResultGivesNoPlanes) {
    const BoundPlanes p = compute_bound_planes(PointCloud{}, GrowResult{}, BoundPlaneConfig{});
    EXPECT_TRUE(p.planes.empty());
    EXPECT_EQ(p.stats.area, 0.0);
    // Points but no surfaces (all noise).
    PointCloud c;
    c.points = {{0, 0, 0}, {1, 1, 1}};
    GrowResult r;
    r.labels = {-1, -1};
    EXPECT_TRUE(compute_bound_planes(c, r, BoundPlaneConfig{}).planes.empty());
}

TEST(BoundPlanes, CollinearPatchesGiveADegeneratePlaneNotACrash) {
    // Two patches whose member points lie on one line (a hand-made result: growing never makes
    // such a plane, but a result file can hold one).
    PointCloud c;
    GrowResult r;
    for (int i = 0; i < 40; ++i) {
        c.points.emplace_back(float(0.001 * i), 0.0f, 0.5f);
        r.labels.push_back(i < 20 ? 0 : 1);
    }
    for (int s = 0; s < 2; ++s) {
        Surface surf;
        surf.home = Vec3d(0.01 + 0.02 * s, 0, 0.5);
        surf.centroid = surf.home;
        surf.normal = Vec3d::UnitZ();
        surf.radius = 0.012;
        surf.neighbours = 20;
        surf.point_count = 20;
        r.surfaces.push_back(surf);
    }
    const BoundPlanes p = compute_bound_planes(c, r, BoundPlaneConfig{});
    ASSERT_EQ(p.planes.size(), 1u);
    const BoundPlane& bp = p.planes[0];
    EXPECT_TRUE(bp.degenerate);
    EXPECT_EQ(p.stats.degenerate, 1u);
    EXPECT_LT(angle_between(bp.normal, Vec3d::UnitZ()), 1e-9);  // from the patches
    EXPECT_TRUE(bp.normal.allFinite());
    EXPECT_GT(bp.area, 0.0);  // a thin strip along the line
    EXPECT_FALSE(mesh_bound_planes(p).triangles.empty());
}

// A plate's end seen head-on: a strip 12 mm wide (x) and 0.5 m tall (z) on the plane y = 0,
// its points spread along the normal by range noise (sigma 5 mm, as a 4-pose fused scan's layers
// give) more deeply than across its width (12 mm uniform: 3.5 mm). Hand-made patches along it,
// 20 mm apart, each with the face's normal, as growing gives them there. The points alone fit the
// plane x = 6 mm: 90 degrees off.
struct Strip {
    PointCloud cloud;
    GrowResult result;
};

// `layer(k)`: how far patch k's points lie behind the face [m], as a scan's layer does.
Strip end_face_strip(std::uint64_t seed, const std::function<double(int)>& layer = {}) {
    Strip s;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> across(0.0, 0.012);
    std::normal_distribution<double> depth(0.0, 0.005);
    constexpr int kPatches = 25, kPerPatch = 60;
    for (int k = 0; k < kPatches; ++k) {
        Surface f;
        Vec3d sum = Vec3d::Zero();
        for (int i = 0; i < kPerPatch; ++i) {
            const Vec3d p(across(rng), depth(rng) + (layer ? layer(k) : 0.0),
                          0.02 * k + 0.02 * i / kPerPatch);
            s.cloud.points.push_back(p.cast<float>());
            s.result.labels.push_back(k);
            sum += p;
        }
        f.home = sum / kPerPatch;
        f.centroid = f.home;
        f.normal = -Vec3d::UnitY();  // facing a sensor at y < 0
        f.radius = 0.012;
        f.neighbours = kPerPatch;
        f.point_count = kPerPatch;
        f.eigenvalues = Vec3d(2.2e-6, 1.6e-5, 2.9e-5);  // a disk's spread: it spans its ball
        s.result.surfaces.push_back(f);
    }
    s.cloud.viewpoint = Vec3d(0.006, -1.0, 0.25);
    return s;
}

TEST(BoundPlanes, AStripNarrowerThanItsNoiseTakesItsPatchesNormal) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        const Strip s = end_face_strip(seed);
        const BoundPlanes p = compute_bound_planes(s.cloud, s.result, BoundPlaneConfig{});
        ASSERT_FALSE(p.planes.empty());
        for (const BoundPlane& bp : p.planes) {
            EXPECT_LT(angle_between(bp.normal, -Vec3d::UnitY()), 1e-6) << seed;
            EXPECT_TRUE(bp.degenerate) << "its points define no plane of their own";
        }
    }
}

TEST(BoundPlanes, AStripNarrowerThanItsNoiseIsOneRegionWhateverItsLayers) {
    // The scans' layers put the patches 0-12 mm behind the face, 2 mm from patch to patch (within
    // the 4.4 mm offset of each other, noise included) but up to 6 mm from the region's mean
    // (beyond it). Along the patches' normal the strip's points spread by noise that deep: the
    // region is not held to its mean's offset, only patch to patch.
    const Strip s = end_face_strip(6, [](int k) {
        constexpr int kWave[] = {0, 2, 4, 6, 8, 10, 12, 10, 8, 6, 4, 2};
        return 0.001 * kWave[k % 12];
    });
    const BoundPlanes p = compute_bound_planes(s.cloud, s.result, BoundPlaneConfig{});
    ASSERT_EQ(p.planes.size(), 1u);
    EXPECT_EQ(p.planes[0].patches.size(), s.result.surfaces.size());
    EXPECT_LT(angle_between(p.planes[0].normal, -Vec3d::UnitY()), 1e-6);
}

TEST(BoundPlanes, AStripNarrowerThanItsNoiseIsNotBridgedToAFaceAcrossItsWidth) {
    // The strip's end meets, across a 30 mm gap, the plate's side: the plane x = 6 mm (normal x),
    // which the strip's points alone would fit. Its patches face -y: the two stay apart.
    Strip s = end_face_strip(4);
    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 0.001);
    const auto strip_patches = static_cast<std::int32_t>(s.result.surfaces.size());
    for (int k = 0; k < 6; ++k) {
        Surface f;
        Vec3d sum = Vec3d::Zero();
        for (int i = 0; i < 10; ++i)
            for (int j = 0; j < 10; ++j) {
                const Vec3d p(0.006 + noise(rng), 0.002 * i, 0.53 + 0.02 * k + 0.002 * j);
                s.cloud.points.push_back(p.cast<float>());
                s.result.labels.push_back(strip_patches + k);
                sum += p;
            }
        f.home = sum / 100;
        f.centroid = f.home;
        f.normal = Vec3d::UnitX();
        f.radius = 0.012;
        f.neighbours = 100;
        f.point_count = 100;
        s.result.surfaces.push_back(f);
    }
    const BoundPlanes p = compute_bound_planes(s.cloud, s.result, BoundPlaneConfig{});
    for (const BoundPlane& bp : p.planes) {
        const bool strip = bp.patches.front() < static_cast<std::uint32_t>(strip_patches);
        for (const std::uint32_t id : bp.patches)
            EXPECT_EQ(id < static_cast<std::uint32_t>(strip_patches), strip) << "one plane";
        EXPECT_LT(angle_between(bp.normal, strip ? Vec3d(-Vec3d::UnitY()) : Vec3d(Vec3d::UnitX())),
                  1.0 * kDeg);
    }
}

TEST(BoundPlanes, PatchesOverruleThePointsOnlyAcrossAndOnlyWhenTheySpanTheirBalls) {
    // A flat plate z = 0 (0.2 x 0.2 m, 1 mm noise) in 16 hand-made patches: its points define
    // its plane, whatever normals its patches claim, unless spanning patches put it across.
    const auto plate = [](const Vec3d& normal, const Vec3d& eigenvalues) {
        Strip s;
        std::mt19937_64 rng(9);
        std::normal_distribution<double> noise(0.0, 0.001);
        for (int k = 0; k < 16; ++k) {
            Surface f;
            Vec3d sum = Vec3d::Zero();
            for (int i = 0; i < 10; ++i)
                for (int j = 0; j < 10; ++j) {
                    const Vec3d p(0.05 * (k % 4) + 0.005 * i, 0.05 * (k / 4) + 0.005 * j,
                                  noise(rng));
                    s.cloud.points.push_back(p.cast<float>());
                    s.result.labels.push_back(k);
                    sum += p;
                }
            f.home = sum / 100;
            f.centroid = f.home;
            f.normal = normal;
            f.radius = 0.03;
            f.neighbours = 100;
            f.point_count = 100;
            f.eigenvalues = eigenvalues;
            s.result.surfaces.push_back(f);
        }
        s.cloud.viewpoint = Vec3d(0.1, 0.1, 1.0);
        return compute_bound_planes(s.cloud, s.result, BoundPlaneConfig{});
    };
    const Vec3d disk(1e-6, 2e-4, 2.2e-4), line(1e-6, 1e-6, 2.2e-4);
    const Vec3d tilted = Vec3d(std::sin(30 * kDeg), 0, std::cos(30 * kDeg));
    for (const auto& [normal, ev, what] :
         {std::tuple{tilted, disk, "spanning patches 30 degrees off"},
          std::tuple{Vec3d(Vec3d::UnitX()), line, "line patches 90 degrees off"}}) {
        const BoundPlanes p = plate(normal, ev);
        ASSERT_FALSE(p.planes.empty()) << what;
        // Unoriented: line patches' normals lie in the plate and cannot say which side faces up.
        EXPECT_GT(std::abs(p.planes[0].normal.z()), std::cos(0.5 * kDeg)) << what;
        EXPECT_FALSE(p.planes[0].degenerate) << what;
    }
    // Spanning patches across it: the plate is taken for the end of a plate seen head-on.
    const BoundPlanes across = plate(Vec3d::UnitX(), disk);
    ASSERT_FALSE(across.planes.empty());
    EXPECT_LT(angle_between(across.planes[0].normal, Vec3d::UnitX()), 1e-6);
}

TEST(BoundPlanes, RefusesInconsistentInputAndBadParameters) {
    const Grown g = grow_rects({kFloor}, 0.0);
    auto code = [&](const PointCloud& c, const GrowResult& r, const BoundPlaneConfig& cfg) {
        try {
            (void)compute_bound_planes(c, r, cfg);
        } catch (const Error& e) {
            return e.code();
        }
        return ErrorCode::kInternal;
    };
    GrowResult short_labels = g.result;
    short_labels.labels.pop_back();
    EXPECT_EQ(code(g.cloud, short_labels, {}), ErrorCode::kInvalidParameter);
    GrowResult bad_label = g.result;
    bad_label.labels[0] = static_cast<std::int32_t>(bad_label.surfaces.size());
    EXPECT_EQ(code(g.cloud, bad_label, {}), ErrorCode::kInvalidParameter);
    GrowResult bad_normal = g.result;
    bad_normal.surfaces[3].normal = Vec3d(0, 0, 2);
    EXPECT_EQ(code(g.cloud, bad_normal, {}), ErrorCode::kInvalidParameter);
    bad_normal.surfaces[3].normal = Vec3d(NAN, 0, 1);
    EXPECT_EQ(code(g.cloud, bad_normal, {}), ErrorCode::kInvalidParameter);
    const auto with = [](auto set) {
        BoundPlaneConfig c;
        set(c);
        return c;
    };
    for (const BoundPlaneConfig& c :
         {with([](auto& c) { c.mu = 0; }), with([](auto& c) { c.mu = -1; }),
          with([](auto& c) { c.max_angle_deg = 0; }), with([](auto& c) { c.max_angle_deg = 90; }),
          with([](auto& c) { c.max_offset = -1e-3; }), with([](auto& c) { c.resolution = NAN; }),
          with([](auto& c) { c.resolution = 1e-9; }), with([](auto& c) { c.max_gap = INFINITY; }),
          with([](auto& c) { c.closing_radius = -1; }), with([](auto& c) { c.threads = -2; }),
          // Beyond float coordinates (1e308 once ended in std::terminate), and an adjacency that
          // pairs every point with thousands (gigabytes within a minute).
          with([](auto& c) { c.closing_radius = 1e308; }),
          with([](auto& c) { c.resolution = 1e39; }), with([](auto& c) { c.max_gap = 1e-300; }),
          with([](auto& c) { c.adjacency = 4.01 * c.mu; })})
        EXPECT_EQ(code(g.cloud, g.result, c), ErrorCode::kInvalidParameter);
    // Large but float lengths give planes, computed on a coarser raster where they must.
    for (const BoundPlaneConfig& c :
         {with([](auto& c) { c.closing_radius = 1e38; }),
          with([](auto& c) { c.resolution = 1e38; }), with([](auto& c) { c.max_gap = 1e38; }),
          with([](auto& c) { c.adjacency = 4 * c.mu; })})
        EXPECT_EQ(compute_bound_planes(g.cloud, g.result, c).planes.size(), 1u);
}

}  // namespace
}  // namespace surfgrow
