// The leftover pass (detail/leftover_pass.hpp) against its definition evaluated by brute force
// over every point: a leftover goes to the best-fitting surface with a member within mu; failing
// that, within 2 mu, 4 mu, ... up to the adaptive radius where it is sparse (or, with the paper's
// test, where nothing at all is within mu), up to 2 mu where it is dense but fits nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/grow_context.hpp"
#include "surfgrow/core/detail/leftover_pass.hpp"
#include "surfgrow/core/noise_profile.hpp"

namespace surfgrow {
namespace {

struct Case {
    std::vector<Vec3f> points;
    std::vector<std::int32_t> grown;  // by input index; -1: a leftover
    std::vector<Surface> surfaces;
    std::vector<double> tolerance;
};

// Clusters of points at random densities (1 to 400 within a mu ball) in a 20 mu box; each point a
// leftover or a member of one of 40 surfaces with random planes through the box, generous
// tolerances so that several surfaces fit most points and the choice among them matters.
Case random_case(std::uint32_t seed, double mu) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Case c;
    const double box = 20 * mu;
    for (int k = 0; k < 40; ++k) {
        Surface s;
        s.normal = Vec3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
        s.centroid = Vec3d(u(rng), u(rng), u(rng)) * box;
        c.surfaces.push_back(s);
        c.tolerance.push_back((0.5 + 4 * u(rng)) * mu);
    }
    for (int cluster = 0; cluster < 30; ++cluster) {
        const Vec3d centre = Vec3d(u(rng), u(rng), u(rng)) * box;
        const double spread = mu * (0.3 + 3 * u(rng));
        const int count = 1 + static_cast<int>(std::pow(400.0, u(rng)));
        const double leftover_share = u(rng);
        const auto own = static_cast<std::int32_t>(rng() % 40);
        for (int i = 0; i < count; ++i) {
            const Vec3d p = centre + spread * Vec3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
            c.points.push_back(p.cast<float>());
            const double pick = u(rng);
            c.grown.push_back(pick < leftover_share ? -1
                              : pick < 0.5 + leftover_share / 2
                                  ? own
                                  : static_cast<std::int32_t>(rng() % 40));
        }
    }
    return c;
}

// The surface that the definition gives sorted point i; -1 if none.
std::int32_t expected_surface(const CubeIndex& index, const GrowerConfig& cfg,
                              std::span<const std::int32_t> labels, const Case& c, std::uint32_t i,
                              std::int32_t first) {
    const Vec3f p = index.local_point(i);
    const Vec3d pw = index.origin() + p.cast<double>();
    // Per surface, its nearest member's squared distance (float, as the index measures); the
    // points within mu, registered or not.
    std::vector<float> nearest(c.surfaces.size(), INFINITY);
    const auto mu = static_cast<float>(cfg.mu);
    int near = 0;
    bool any = false;
    for (std::uint32_t j = 0; j < index.size(); ++j) {
        const Vec3f q = index.local_point(j);
        const float dx = q.x() - p.x(), dy = q.y() - p.y(), dz = q.z() - p.z();
        const float d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= mu * mu) {
            ++near;
            any = any || labels[j] >= 0;
        }
        if (labels[j] >= 0) {
            float& m = nearest[static_cast<std::size_t>(labels[j])];
            m = std::min(m, d2);
        }
    }
    // The best-fitting surface with a member within radius; ties to the lower id.
    auto best = [&](double radius) {
        const auto r = static_cast<float>(radius);
        std::int32_t b = -1;
        double bd = 0;
        for (auto k = static_cast<std::size_t>(first); k < c.surfaces.size(); ++k) {
            const Surface& s = c.surfaces[k];
            const double d = std::abs(s.normal.dot(pw - s.centroid));
            if (d <= c.tolerance[k] && nearest[k] <= r * r && (b < 0 || d < bd)) {
                b = static_cast<std::int32_t>(k);
                bd = d;
            }
        }
        return b;
    };
    std::int32_t b = best(cfg.mu);
    if (b >= 0) return b;
    const bool disk = cfg.plane_test == PlaneTest::kDisk;
    if (!disk && any) return -1;
    const bool sparse = !any && near < cfg.min_pts;
    const double limit =
        sparse || !disk ? cfg.max_radius() : std::min(cfg.max_radius(), 2 * cfg.mu);
    for (double r = 2 * cfg.mu; b < 0; r *= 2) {
        b = best(std::min({r, limit, cfg.max_radius()}));
        if (std::min(r, cfg.max_radius()) >= limit) break;
    }
    return b;
}

void check(std::uint32_t seed, PlaneTest test, int threads, std::int32_t first = 0) {
    GrowerConfig cfg;
    cfg.mu = 0.012;
    cfg.plane_test = test;
    const Case c = random_case(seed, cfg.mu);
    const CubeIndex index(c.points, cfg.mu, {}, 1);
    const auto n = static_cast<std::uint32_t>(index.size());
    std::vector<std::int32_t> labels(n + CubeIndex::kPadding, -1);
    const auto orig = index.original_indices();
    for (std::uint32_t i = 0; i < n; ++i) labels[i] = c.grown[orig[i]];
    const std::vector<std::int32_t> grown(labels.begin(), labels.begin() + n);
    std::vector<float> distance(n, 0.f);
    const detail::SensorSight sight;
    const NoiseProfile noise, layers;
    const detail::GrowContext ctx{
        index, cfg, std::span<std::int32_t>(labels.data(), n), distance, sight, noise, layers};
    // Three slabs, so that neighbourhoods cross slab boundaries.
    const auto cubes = static_cast<std::uint32_t>(index.cube_count());
    const std::vector<detail::Slab> slabs = {
        {0, cubes / 3}, {cubes / 3, 2 * cubes / 3}, {2 * cubes / 3, cubes}};
    detail::attach_leftovers(ctx, slabs, c.surfaces, c.tolerance, threads,
                             std::span<std::int32_t>(labels.data(), n), first);
    int attached = 0, left = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (grown[i] >= 0) {
            ASSERT_EQ(labels[i], grown[i]) << "a grown point moved";
            continue;
        }
        const std::int32_t want = expected_surface(index, cfg, grown, c, i, first);
        ASSERT_EQ(labels[i], want) << "seed " << seed << ", point " << i;
        (want >= 0 ? attached : left) += 1;
    }
    // Both outcomes occur (else the case tests nothing).
    EXPECT_GT(attached, 0);
    EXPECT_GT(left, 0);
}

TEST(LeftoverPass, MatchesItsDefinitionByBruteForceWithTheDiskTest) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) check(seed, PlaneTest::kDisk, 2);
}

TEST(LeftoverPass, AfterStripsOnlyTheStripsTakePoints) {
    // Surfaces 30 to 39 stand for the strips: only they may take a point, though every
    // registered point still counts as a neighbour.
    for (std::uint32_t seed = 21; seed <= 24; ++seed) check(seed, PlaneTest::kDisk, 2, 30);
}

TEST(LeftoverPass, MatchesItsDefinitionByBruteForceWithThePapersTest) {
    for (std::uint32_t seed = 11; seed <= 14; ++seed) check(seed, PlaneTest::kPaper, 1);
}

// Fused clouds: a floor (z = 0) grown from scan 0, and scan 1's leftovers beside it, 2 mm of noise
// within a layer, the scans' layers 3 mm apart (sigma). Scan 1's layer of the floor 8 mm and
// 10.5 mm (3.5 sigmas) above it joins the floor; a narrow face's band across the floor (a
// vertical strip 2-11 mm above it, a flange edge's leftovers beside the deck) does not, though it
// is as thin along the floor's normal as a layer may be and each of its points lies within the
// floor's tolerance of the band's median distance.
TEST(LeftoverPass, AScansOffsetLayerJoinsTheFaceButABandAcrossItDoesNot) {
    GrowerConfig cfg;
    cfg.mu = 0.012;
    std::vector<Vec3f> points;
    std::vector<std::uint32_t> scan;
    std::vector<std::int32_t> grown;
    enum Part : int { kFloor, kLayer, kFarLayer, kBand };
    std::vector<int> part;
    auto add = [&](double x, double y, double z, std::uint32_t s, int what) {
        points.emplace_back(float(x), float(y), float(z));
        scan.push_back(s);
        grown.push_back(what == kFloor ? 0 : -1);
        part.push_back(what);
    };
    for (int i = -40; i <= 40; ++i)
        for (int j = -20; j <= 20; ++j) add(0.005 * i, 0.005 * j, 0.0, 0, kFloor);
    for (int i = 0; i <= 8; ++i)
        for (int j = -4; j <= 4; ++j) {
            add(0.04 + 0.005 * i, 0.005 * j, 0.008, 1, kLayer);
            add(-0.12 + 0.005 * i, 0.005 * j, 0.0105, 1, kFarLayer);
        }
    for (int j = -8; j <= 8; ++j)
        for (const double z : {0.002, 0.005, 0.008, 0.011}) add(-0.05, 0.005 * j, z, 1, kBand);

    Surface floor;
    floor.home = floor.centroid = Vec3d::Zero();
    floor.normal = Vec3d::UnitZ();
    floor.radius = 0.2;
    const std::vector<Surface> surfaces{floor};
    const std::vector<double> tolerance{0.004};

    const CubeIndex index(points, cfg.mu, {}, 1);
    const auto n = static_cast<std::uint32_t>(index.size());
    const auto orig = index.original_indices();
    std::vector<std::int32_t> labels(n + CubeIndex::kPadding, -1);
    for (std::uint32_t i = 0; i < n; ++i) labels[i] = grown[orig[i]];
    std::vector<float> distance(n, 0.f);
    detail::SensorSight sight;
    sight.origins = {index.to_local(Vec3d(0, 0, 1)), index.to_local(Vec3d(0.05, 0, 1))};
    sight.named = true;
    sight.scan_index = scan;
    sight.original = orig;
    ASSERT_TRUE(sight.fused());
    const std::vector<ThicknessSample> noise_samples(32, {-1, 0.002}),
        layer_samples(32, {-1, 0.003});
    const NoiseProfile noise(noise_samples, 0, 1e-6), layers(layer_samples, 0, 1e-6);
    ASSERT_NEAR(layers.sigma(1.0), 0.003, 1e-9);
    const detail::GrowContext ctx{
        index, cfg, std::span<std::int32_t>(labels.data(), n), distance, sight, noise, layers};
    const std::vector<detail::Slab> slabs = {{0, static_cast<std::uint32_t>(index.cube_count())}};
    detail::attach_leftovers(ctx, slabs, surfaces, tolerance, 1,
                             std::span<std::int32_t>(labels.data(), n));
    int layer = 0, layer_in = 0, far = 0, far_in = 0, band_off = 0, band_off_in = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t k = orig[i];
        const bool in = labels[i] == 0;
        if (part[k] == kLayer) ++layer, layer_in += in;
        if (part[k] == kFarLayer) ++far, far_in += in;
        // The band's points beyond the floor's tolerance could only join it as a layer; at its
        // ends the band within mu holds too few points to fix its plane, and is not judged so.
        if (part[k] == kBand && points[k].z() > 0.0045f && std::abs(points[k].y()) < 0.031f)
            ++band_off, band_off_in += in;
    }
    EXPECT_EQ(layer_in, layer);
    EXPECT_EQ(far_in, far);  // 3.5 sigmas: within the budget for a cloud's largest offsets
    EXPECT_GT(band_off, 30);
    EXPECT_EQ(band_off_in, 0);
}

}  // namespace
}  // namespace surfgrow
