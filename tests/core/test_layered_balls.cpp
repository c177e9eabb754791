// Fused clouds are stacks of layers: each scan sees a surface a little off the others along its
// rays (its range bias, its pose error). Where the offsets outweigh the noise (a far floor seen at
// a grazing angle), every ball holding two scans is thick: it must be judged within its layers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "support/test_support.hpp"
#include "surfgrow/core/plane_fit.hpp"
#include "surfgrow/core/surface_grower.hpp"

namespace surfgrow {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Three scans 0.5 m apart, 1.45 m above a floor (label 0) and 1 m from a wall (label 1), as the
// channel's scan path stands. Each scan samples both on its own jittered grid; then every point
// moves along its ray by the scan's offset for that face (its range bias) and by range noise.
struct LayeredScene {
    PointCloud cloud;
    std::vector<Vec3d> normals{Vec3d::UnitZ(), Vec3d::UnitY()};
    std::vector<std::uint8_t> interior;  // per point: more than 60 mm inside its face's edges
};

LayeredScene layered_scene(double floor_offset_m) {
    LayeredScene s;
    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 0.002);
    // The wall, 1 m away and dense, is most of the cloud: the noise is measured there, and its
    // layers lie 1 mm apart. The floor, 2.7-3.1 m away at 60-65 degrees, is sparse and too small
    // to set the noise of its range bands (where a floor fills them, its layers count as noise).
    const test::Rect wall{{0, 1.0, 1.45}, Vec3d::UnitX(), Vec3d::UnitZ(), 1.0, 0.6};
    const test::Rect floor{{0, 2.9, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.4, 0.2};
    for (std::uint32_t k = 0; k < 3; ++k) {
        const Vec3d origin(-0.5 + 0.5 * k, 0, 1.45);
        s.cloud.scan_origins.push_back(origin);
        for (int f = 0; f < 2; ++f) {
            const test::Rect& rect = f == 0 ? floor : wall;
            std::vector<Vec3f> points;
            test::sample_rect(rect, f == 0 ? 0.02 : 0.005, 0.4, 0.0, rng, points);
            // Scan 0 sees the face `offset` farther, scan 2 as much nearer.
            const double offset = (1.0 - k) * (f == 0 ? floor_offset_m : 0.001);
            for (const Vec3f& p : points) {
                const Vec3d d = p.cast<double>() - rect.center;
                s.interior.push_back(std::abs(d.dot(rect.u)) < rect.half_u - 0.06 &&
                                     std::abs(d.dot(rect.v)) < rect.half_v - 0.06);
                const Vec3d ray = (p.cast<double>() - origin).normalized();
                s.cloud.points.push_back(
                    (p.cast<double>() + (offset + noise(rng)) * ray).cast<float>());
                s.cloud.labels.push_back(f);
                s.cloud.scan_index.push_back(k);
            }
        }
    }
    return s;
}

// The floor's interior (a floating rectangle's rim is an edge every scan's layer ends at
// somewhere else) and the wall.
struct Outcome {
    double floor_registered = 0;
    double floor_p95_deg = 0;  // their surfaces' normal error
    double floor_over_45 = 0;  // share of the floor's points more than 45 degrees off
    double wall_registered = 0;
};

Outcome grow(const LayeredScene& s) {
    const GrowResult r = grow_surfaces(s.cloud, GrowerConfig{});
    std::vector<double> err;
    std::size_t floor = 0, wall = 0, wall_registered = 0, over = 0;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
        const std::int32_t l = r.labels[i];
        if (s.cloud.labels[i] == 1) {
            ++wall;
            wall_registered += l >= 0 ? 1 : 0;
            continue;
        }
        if (!s.interior[i]) continue;
        ++floor;
        if (l < 0) continue;
        err.push_back(
            axis_angle_between(r.surfaces[static_cast<std::size_t>(l)].normal, s.normals[0]));
        over += err.back() > 45 * kDeg ? 1 : 0;
    }
    Outcome o;
    o.floor_registered = double(err.size()) / double(floor);
    o.floor_p95_deg = err.empty() ? 90 : test::quantile(err, 0.95) / kDeg;
    o.floor_over_45 = double(over) / double(floor);
    o.wall_registered = double(wall_registered) / double(wall);
    std::printf("floor %.2f %% registered, p95 %.2f deg, %.2f %% > 45 deg; wall %.2f %%\n",
                100 * o.floor_registered, o.floor_p95_deg, 100 * o.floor_over_45,
                100 * o.wall_registered);
    return o;
}

TEST(LayeredBalls, AFarFloorWhoseScansLieApartAlongTheirRaysGrowsWithItsOwnNormal) {
    // Range biases of +15, 0 and -15 mm: along the floor's normal its layers lie 7 mm apart,
    // three noise sigmas, across balls that hold a few points of each scan. Judged as one they
    // lean: p95 13 degrees.
    const Outcome o = grow(layered_scene(0.015));
    EXPECT_GE(o.wall_registered, 0.99);
    EXPECT_GE(o.floor_registered, 0.99);
    EXPECT_LT(o.floor_p95_deg, 5.0);
    EXPECT_LE(o.floor_over_45, 0.005);
}

TEST(LayeredBalls, LayersTheDatasheetsAccuracyAllowsAtThreeMetresHeldToTheirMeasuredLevel) {
    // +-30 mm, the URG's +-1 % of range at 3 m: every ball holding two scans is thick. Judged as
    // one, 80 % of the floor registered, p95 56 degrees, 5 % more than 45 degrees off; judged
    // within its layers 97 %, 7.6 degrees (2026-12-07), none. With a tolerance that spans the
    // layers (the plane lies between them: with the noise's alone, the outer layers' farther
    // halves stayed out) 100 %, 8.1 degrees, 0.2 %.
    const Outcome o = grow(layered_scene(0.03));
    EXPECT_GE(o.wall_registered, 0.99);
    EXPECT_GE(o.floor_registered, 0.99);
    EXPECT_LT(o.floor_p95_deg, 10.0);
    EXPECT_LE(o.floor_over_45, 0.005);
}

TEST(LayeredBalls, LayersThatAgreeGrowAsOne) {
    const Outcome o = grow(layered_scene(0.001));
    EXPECT_GE(o.floor_registered, 0.99);
    EXPECT_LT(o.floor_p95_deg, 2.0);
    EXPECT_LE(o.floor_over_45, 0.0);
}

}  // namespace
}  // namespace surfgrow
