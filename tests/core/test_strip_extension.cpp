// extend_strips (detail/strip_growing.hpp): a strip reaches along its face, step by step, to the
// points its ball could not hold (a flange's edge far from the sensor: two scan lines), judged
// against the plane of all its members; nothing off that plane or beyond a gap joins, and every
// member ends within the strip's tolerance of its final plane. extend_surfaces: any surface
// reaches so from the points registered since growing, keeping its plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/grow_context.hpp"
#include "surfgrow/core/detail/strip_growing.hpp"
#include "surfgrow/core/noise_profile.hpp"

namespace surfgrow {
namespace {

enum Part : int { kFloorPart, kStripMember, kFarEnd, kBeyondGap, kAcross, kFloorLeftover };

struct Scene {
    std::vector<Vec3f> points;
    std::vector<std::int32_t> grown;  // by input index; -1: a leftover
    std::vector<int> part;
    std::vector<Surface> surfaces;  // 0: a floor (not a strip), 1: the strip
    std::vector<double> tolerance;
};

// A 20 mm edge face in the plane y = 0 (z from 0 to 20 mm), noise 1 mm along y. Its first 100 mm
// are the strip's members, as grown from one ball; then two scan lines 8 mm apart run on to
// x = 0.5 m with 20 mm between points (leftovers), and after a 150 mm gap on to 0.8 m. A face
// across the strip (the plane x = 0.6 m, leftovers) and a floor (z = -0.05 m, grown, with
// leftovers of its own) stand beside it. The strip's stored normal leans 3 degrees about z, as a
// short ball's normal does: 0.4 m along, that plane lies 21 mm off the face.
Scene edge_scene(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.001);
    Scene s;
    auto add = [&](double x, double y, double z, int what) {
        s.points.emplace_back(float(x), float(y), float(z));
        s.grown.push_back(what == kStripMember ? 1 : what == kFloorPart ? 0 : -1);
        s.part.push_back(what);
    };
    for (double x = 0; x <= 0.1; x += 0.005)
        for (double z = 0.002; z < 0.02; z += 0.004) add(x, noise(rng), z, kStripMember);
    for (double x = 0.11; x <= 0.5; x += 0.02) {
        add(x, noise(rng), 0.006, kFarEnd);
        add(x + 0.01, noise(rng), 0.014, kFarEnd);
    }
    for (double x = 0.65; x <= 0.8; x += 0.02) add(x, noise(rng), 0.01, kBeyondGap);
    for (double y = 0.01; y <= 0.1; y += 0.01)
        for (double z = 0.0; z <= 0.02; z += 0.01) add(0.52, y, z, kAcross);
    for (double x = 0; x <= 0.3; x += 0.01)
        for (double y = -0.1; y <= -0.02; y += 0.01)
            add(x, y, -0.05 + noise(rng), x < 0.2 ? kFloorPart : kFloorLeftover);

    Surface floor;
    floor.home = floor.centroid = Vec3d(0.1, -0.06, -0.05);
    floor.normal = Vec3d::UnitZ();
    floor.radius = 0.024;
    floor.tolerance = 0.004;
    Surface strip;
    strip.home = Vec3d(0.05, 0, 0.01);
    strip.centroid = strip.home;
    const double lean = 3 * M_PI / 180;
    strip.normal = Vec3d(std::sin(lean), std::cos(lean), 0);
    strip.radius = 0.034;
    strip.tolerance = 0.004;
    s.surfaces = {floor, strip};
    s.tolerance = {floor.tolerance, strip.tolerance};
    return s;
}

// The scene as the grower's stages see it: indexed at mu = 12 mm, its labels in the index's
// order (each input label through `relabel`), no sensor and no noise profile.
struct Indexed {
    static constexpr double kMu = 0.012;
    Indexed(const Scene& s, std::int32_t (*relabel)(std::int32_t))
        : index(s.points, kMu, {}, 1),
          n(static_cast<std::uint32_t>(index.size())),
          orig(index.original_indices()),
          labels(n + CubeIndex::kPadding, -1),
          distance(n, 0.f) {
        cfg.mu = kMu;
        for (std::uint32_t i = 0; i < n; ++i) labels[i] = relabel(s.grown[orig[i]]);
    }
    [[nodiscard]] detail::GrowContext context() {
        return {index, cfg,   std::span<std::int32_t>(labels.data(), n), distance, sight,
                noise, layers};
    }

    GrowerConfig cfg;
    CubeIndex index;
    std::uint32_t n;
    std::span<const std::uint32_t> orig;
    std::vector<std::int32_t> labels;
    std::vector<float> distance;
    detail::SensorSight sight;
    NoiseProfile noise, layers;
};

TEST(StripExtension, AStripReachesAlongItsFaceToItsFarEndAndNoFurther) {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        Scene s = edge_scene(seed);
        Indexed x(s, [](std::int32_t l) { return l; });
        const CubeIndex& index = x.index;
        const std::uint32_t n = x.n;
        const auto orig = x.orig;
        const std::vector<std::int32_t>& labels = x.labels;
        ASSERT_EQ(n, s.points.size());
        const std::int64_t gained = detail::extend_strips(x.context(), 1, s.surfaces, s.tolerance);

        const Surface& strip = s.surfaces[1];
        // The plane of its members: the face's. Its lean about z (3 degrees) is gone: half a metre
        // of points fixes it to hundredths of a degree. About the strip's long axis the 20 mm
        // width and 1 mm of noise fix it to about a degree (sigma / (sqrt(n) * RMS width)).
        EXPECT_LT(std::abs(strip.normal.x()), std::sin(0.2 * M_PI / 180)) << "seed " << seed;
        EXPECT_GT(std::abs(strip.normal.y()), std::cos(3 * M_PI / 180)) << "seed " << seed;
        std::int64_t far_taken = 0, far = 0, members = 0;
        const auto members_before = std::count(s.grown.begin(), s.grown.end(), 1);
        for (std::uint32_t i = 0; i < n; ++i) {
            const int part = s.part[orig[i]];
            const std::int32_t l = labels[i];
            if (l == 1) {
                ++members;
                const double d = std::abs(strip.normal.dot(index.world_point(i) - strip.centroid));
                EXPECT_LE(d, strip.tolerance) << "seed " << seed << ", a member off the plane";
            }
            switch (part) {
                case kFloorPart:
                    EXPECT_EQ(l, 0);
                    break;
                case kFarEnd:
                    ++far;
                    far_taken += l == 1 ? 1 : 0;
                    break;
                // Beyond a gap wider than its reach, off its plane, or another surface's leftover.
                case kBeyondGap:
                case kAcross:
                case kFloorLeftover:
                    EXPECT_EQ(l, -1) << "seed " << seed << ", part " << part;
                    break;
                default:
                    break;
            }
        }
        // The far end's points lie within the noise of the face: all but a stray few join.
        EXPECT_GE(double(far_taken), 0.95 * double(far)) << "seed " << seed;
        EXPECT_EQ(gained + members_before, members) << "seed " << seed;
    }
}

TEST(StripExtension, NoStripsNoChange) {
    Scene s = edge_scene(1);
    // The strip's members as the floor's: no surface from 1 on.
    Indexed x(s, [](std::int32_t l) { return l == 1 ? 0 : l; });
    const std::vector<std::int32_t> before = x.labels;
    s.surfaces.resize(1);  // the floor alone: first_strip 1 names none
    s.tolerance.resize(1);
    EXPECT_EQ(detail::extend_strips(x.context(), 1, s.surfaces, s.tolerance), 0);
    EXPECT_EQ(x.labels, before);
}

// A wall (the plane z = 0, noise 1 mm) seen at grazing incidence far from the sensor: a surface
// grown where it was dense enough (radius 96 mm, its ball grown for the spacing), then a line of
// points 60 mm apart on to x = 0.8 m, the first of which the leftover pass took (within 96 mm of a
// member). Beside it a line as sparse 20 mm off the wall (beyond the 4 mm tolerance), and after a
// 150 mm gap a line on the wall again (beyond the reach).
enum FarPart : int { kGrown, kFarLine, kOffLine, kPastGap };

struct FarWall {
    std::vector<Vec3f> points;
    std::vector<std::int32_t> grown;
    std::vector<int> part;
    std::vector<Surface> surfaces;
    std::vector<double> tolerance;
};

FarWall far_wall(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.001);
    FarWall w;
    auto add = [&](double x, double y, double z, int what, std::int32_t label) {
        w.points.emplace_back(float(x), float(y), float(z));
        w.grown.push_back(label);
        w.part.push_back(what);
    };
    for (double x = 0; x <= 0.2; x += 0.03)
        for (double y = 0; y <= 0.12; y += 0.03) add(x, y, noise(rng), kGrown, 0);
    add(0.26, 0.06, noise(rng), kFarLine, 0);  // taken by the leftover pass
    for (double x = 0.32; x <= 0.8; x += 0.06) add(x, 0.06, noise(rng), kFarLine, -1);
    for (double x = 0.29; x <= 0.8; x += 0.06) add(x, 0.09, 0.02 + noise(rng), kOffLine, -1);
    for (double x = 0.95; x <= 1.2; x += 0.06) add(x, 0.06, noise(rng), kPastGap, -1);
    Surface wall;
    wall.home = wall.centroid = Vec3d(0.1, 0.06, 0);
    wall.normal = Vec3d::UnitZ();
    wall.radius = 0.096;
    wall.tolerance = 0.004;
    w.surfaces = {wall};
    w.tolerance = {wall.tolerance};
    return w;
}

TEST(SurfaceExtension, AFarFaceJoinsTheSurfaceGrownNearerStepByStep) {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        FarWall w = far_wall(seed);
        Scene as_scene;
        as_scene.points = w.points;
        as_scene.grown = w.grown;
        Indexed x(as_scene, [](std::int32_t l) { return l; });
        ASSERT_EQ(x.n, w.points.size());
        // The frontier: the points registered since growing (the one the leftover pass took).
        std::vector<std::uint32_t> frontier;
        for (std::uint32_t i = 0; i < x.n; ++i)
            if (w.part[x.orig[i]] == kFarLine && x.labels[i] == 0) frontier.push_back(i);
        ASSERT_EQ(frontier.size(), 1u);
        const std::int64_t gained =
            detail::extend_surfaces(x.context(), w.surfaces, w.tolerance, frontier);
        std::int64_t far = 0, far_taken = 0;
        for (std::uint32_t i = 0; i < x.n; ++i) {
            const int part = w.part[x.orig[i]];
            const std::int32_t l = x.labels[i];
            if (part == kFarLine) {
                ++far;
                far_taken += l == 0 ? 1 : 0;
            }
            if (part == kOffLine || part == kPastGap) {
                EXPECT_EQ(l, -1) << "seed " << seed;
            }
            if (part == kGrown) {
                EXPECT_EQ(l, 0);
            }
        }
        EXPECT_EQ(far_taken, far) << "seed " << seed;  // every point of the line, 60 mm apart
        EXPECT_EQ(gained, far - 1) << "seed " << seed;
        // The surface keeps its plane (its normal was pooled; a strip's is refitted).
        EXPECT_EQ(w.surfaces[0].normal, Vec3d::UnitZ());
        EXPECT_EQ(w.surfaces[0].centroid, Vec3d(0.1, 0.06, 0));
    }
}

TEST(SurfaceExtension, NothingTakenSinceGrowingNoChange) {
    FarWall w = far_wall(1);
    Scene as_scene;
    as_scene.points = w.points;
    as_scene.grown = w.grown;
    Indexed x(as_scene, [](std::int32_t l) { return l; });
    const std::vector<std::int32_t> before = x.labels;
    EXPECT_EQ(detail::extend_surfaces(x.context(), w.surfaces, w.tolerance, {}), 0);
    EXPECT_EQ(x.labels, before);
}

}  // namespace
}  // namespace surfgrow
