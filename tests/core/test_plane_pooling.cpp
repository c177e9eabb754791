// Normal pooling and its lone-patch rules (plane_pooling.hpp) on patches cut from analytic
// surfaces: two faces at a depth step with a mixed-pixel ramp between them, and a narrow real face.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "surfgrow/core/plane_fit.hpp"
#include "surfgrow/core/plane_pooling.hpp"

namespace surfgrow {
namespace {

struct Strip {
    Vec3d origin;     // a corner
    Vec3d across;     // unit, in the surface
    double width;     // along `across`
    int columns = 0;  // lines of points across it; 0: one every `spacing`
};

// Points on a 5 mm grid (the URG-04LX's spacing at about 1 m), y from -0.1 to 0.1 m, Gaussian
// noise along the strip's normal; one vector of points per strip.
std::vector<std::vector<Vec3d>> sample(const std::vector<Strip>& strips, double spacing,
                                       double sigma, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<std::vector<Vec3d>> out;
    for (const Strip& s : strips) {
        const Vec3d normal = s.across.cross(Vec3d::UnitY()).normalized();
        std::vector<Vec3d> pts;
        const int columns = s.columns > 0
                                ? s.columns
                                : std::max(1, static_cast<int>(std::round(s.width / spacing)) + 1);
        for (int c = 0; c < columns; ++c)
            for (double y = -0.1; y <= 0.1 + 1e-9; y += spacing) {
                const double t = s.columns > 0 ? s.width * (c + 0.5) / columns
                                               : s.width * c / std::max(1, columns - 1);
                pts.push_back(s.origin + t * s.across + y * Vec3d::UnitY() + noise(rng) * normal);
            }
        out.push_back(std::move(pts));
    }
    return out;
}

// A patch at every second point of each strip: its strip's points within `radius`, as growing
// registers them (a patch never holds another surface's points here).
std::vector<PoolablePatch> patches_of(const std::vector<std::vector<Vec3d>>& strips, double radius,
                                      std::vector<int>& strip_of) {
    std::vector<PoolablePatch> out;
    for (std::size_t k = 0; k < strips.size(); ++k)
        for (std::size_t h = 0; h < strips[k].size(); h += 2) {
            const Vec3d home = strips[k][h];
            Moments m;
            for (const Vec3d& p : strips[k])
                if ((p - home).norm() <= radius) m.add(p - home);
            const PlaneFit fit = fit_plane(m);
            out.push_back({home, home + fit.centroid, fit.normal, fit.eigenvalues[0], m});
            strip_of.push_back(static_cast<int>(k));
        }
    return out;
}

PoolingConfig pooling() {
    PoolingConfig pc;
    pc.radius = 0.024;  // 2 mu at mu = 12 mm
    pc.max_angle = 15 * M_PI / 180;
    pc.min_offset = 0.0012;
    pc.max_offset = 0.006;
    return pc;
}

// Face A (z = 0, x < 0), face B (z = 12 mm, x > 5 mm) and between them the ramp a depth edge's
// mixed pixels make: the readings whose footprint straddles the edge, two lines of them, the ramp
// 67 degrees off both faces.
std::vector<Strip> depth_step() {
    return {{{-0.15, 0, 0}, Vec3d::UnitX(), 0.15},
            {{0.005, 0, 0.012}, Vec3d::UnitX(), 0.145},
            {{0.0, 0, 0.0}, Vec3d(0.005, 0, 0.012).normalized(), 0.013, 2}};
}

TEST(PlanePooling, CoplanarPatchesPoolIntoABetterNormalAndEdgesDoNot) {
    std::vector<int> strip_of;
    const auto strips =
        sample({{{-0.15, 0, 0}, Vec3d::UnitX(), 0.15}, {{0.0, 0, 0.0}, Vec3d::UnitZ(), 0.15}},
               0.005, 0.0015, 1);
    const auto patches = patches_of(strips, 0.012, strip_of);
    const std::vector<Vec3d> pooled = pool_normals(patches, pooling());
    ASSERT_EQ(pooled.size(), patches.size());
    const Vec3d truth[] = {Vec3d::UnitZ(), Vec3d::UnitX()};
    double own = 0, after = 0;
    for (std::size_t k = 0; k < patches.size(); ++k) {
        const Vec3d t = truth[strip_of[k]];
        own += std::acos(std::min(1.0, std::abs(patches[k].normal.dot(t))));
        const double e = std::acos(std::min(1.0, std::abs(pooled[k].dot(t))));
        after += e;
        // Never pooled across the edge: every pooled normal is its own face's.
        EXPECT_LT(e, 10 * M_PI / 180) << "patch " << k;
        EXPECT_NEAR(pooled[k].norm(), 1.0, 1e-12);
        EXPECT_GT(pooled[k].dot(patches[k].normal), 0.0);  // the patch's own sign
    }
    EXPECT_LT(after, 0.5 * own);  // tens of coplanar neighbours: several times more accurate
}

TEST(PlanePooling, AMixedPixelRampBetweenTwoFacesIsAMinorityAndTheFacesAreNot) {
    std::vector<int> strip_of;
    const auto patches = patches_of(sample(depth_step(), 0.005, 0.0005, 2), 0.012, strip_of);
    std::vector<std::uint8_t> lone;
    (void)pool_normals(patches, pooling(), lone, LoneRule{3, 0.2});
    ASSERT_EQ(lone.size(), patches.size());
    std::size_t ramp = 0, ramp_lone = 0, face_lone = 0;
    for (std::size_t k = 0; k < patches.size(); ++k) {
        if (strip_of[k] == 2) {
            ++ramp;
            ramp_lone += lone[k];
        } else {
            face_lone += lone[k];
        }
    }
    ASSERT_GT(ramp, 10u);
    EXPECT_EQ(ramp_lone, ramp);
    EXPECT_EQ(face_lone, 0u);
    // The ramp's patches agree with one another, so the older rule alone (none in its plane)
    // keeps them; without a minority share nothing is marked.
    (void)pool_normals(patches, pooling(), lone, LoneRule{3, 0.0});
    for (std::size_t k = 0; k < patches.size(); ++k) EXPECT_EQ(lone[k], 0) << "patch " << k;
    // No rule: nothing marked, nothing to mark with.
    (void)pool_normals(patches, pooling(), lone, LoneRule{});
    EXPECT_TRUE(lone.empty());
}

TEST(PlanePooling, ANarrowRealFaceBetweenTwoFacesIsKept) {
    // A 30 mm step face (a flange edge) from face A up to face B, square to both.
    std::vector<int> strip_of;
    const auto patches = patches_of(sample({{{-0.15, 0, 0}, Vec3d::UnitX(), 0.15},
                                            {{0.0, 0, 0.0}, Vec3d::UnitZ(), 0.03},
                                            {{0.0, 0, 0.03}, Vec3d::UnitX(), 0.15}},
                                           0.005, 0.0005, 3),
                                    0.012, strip_of);
    std::vector<std::uint8_t> lone;
    (void)pool_normals(patches, pooling(), lone, LoneRule{3, 0.2});
    for (std::size_t k = 0; k < patches.size(); ++k)
        EXPECT_EQ(lone[k], 0) << "patch " << k << " of strip " << strip_of[k];
}

TEST(PlanePooling, TheSameForAnyThreadCount) {
    std::vector<int> strip_of;
    const auto patches = patches_of(sample(depth_step(), 0.005, 0.0015, 4), 0.012, strip_of);
    PoolingConfig one = pooling(), two = pooling();
    two.threads = 2;
    std::vector<std::uint8_t> lone1, lone2;
    const auto a = pool_normals(patches, one, lone1, LoneRule{3, 0.2});
    const auto b = pool_normals(patches, two, lone2, LoneRule{3, 0.2});
    EXPECT_EQ(lone1, lone2);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k], b[k]);
}

}  // namespace
}  // namespace surfgrow
