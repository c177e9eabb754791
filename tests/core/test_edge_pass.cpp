// The edge pass (stage 3c of growing, fused clouds): a point that best fit against the planes
// alone gave to the face across an edge goes back to its own face once each surface's plane is
// shifted to the point's own scan's layer; points on the right face and points between coplanar
// surfaces stay where they are; the result does not depend on the thread count; a single scan is
// left alone.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/edge_pass.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/noise_profile.hpp"

namespace surfgrow {
namespace {

// A floor (z = 0, x < 0) and a wall (x = 0, z > 0) meeting along the y axis, seen by two scans,
// +-0.5 mm of noise. Scan 1 sees the floor 4 mm high (its layer: range bias, pose error) and the
// wall where scan 0 does. The floor is two coplanar surfaces, split 10 mm from the wall so that
// both reach the edge; the wall is one.
struct EdgeCase {
    enum Part : int { kFloor, kWall };
    std::vector<Vec3f> points;
    std::vector<std::uint32_t> scan;
    std::vector<int> part;
    std::vector<std::int32_t> grown;  // labels as best fit against the planes alone leaves them
    std::vector<Surface> surfaces;
    std::vector<double> tolerance{0.006, 0.006, 0.006};

    EdgeCase() {
        std::uint32_t draw = 0;
        auto noise = [&] {  // uniform in +-0.5 mm, the same every run
            draw = draw * 1664525u + 1013904223u;
            return 0.001 * (double(draw >> 8) / double(1u << 24) - 0.5);
        };
        auto add = [&](double x, double y, double z, std::uint32_t s, int what) {
            points.emplace_back(float(x), float(y), float(z));
            scan.push_back(s);
            part.push_back(what);
            std::int32_t label = what == kWall ? 2 : (x < -0.01 ? 0 : 1);
            // Scan 1's floor layer 4 mm up: within 4 mm of the wall it lies nearer the wall's
            // plane (x = 0) than the floor's (z = 0).
            if (what == kFloor && s == 1 && x > -0.004) label = 2;
            grown.push_back(label);
        };
        for (std::uint32_t s = 0; s < 2; ++s) {
            const double shift = 0.001 * s;  // the scans' points interleave
            for (int i = 0; i < 60; ++i)
                for (int j = -40; j <= 40; ++j) {
                    const double along = -0.0015 - 0.0025 * i - shift, y = 0.0025 * j + shift;
                    add(along, y, (s == 1 ? 0.004 : 0.0) + noise(), s, kFloor);
                    add(noise(), y, 0.0045 + 0.0025 * i + shift, s, kWall);
                }
        }
        auto surface = [](const Vec3d& centroid, const Vec3d& normal) {
            Surface s;
            s.home = s.centroid = centroid;
            s.normal = normal;
            s.radius = 0.05;
            return s;
        };
        surfaces = {surface({-0.08, 0, 0}, Vec3d::UnitZ()), surface({-0.005, 0, 0}, Vec3d::UnitZ()),
                    surface({0, 0, 0.075}, Vec3d::UnitX())};
    }
};

struct Outcome {
    std::vector<std::int32_t> labels;  // input order
    std::uint64_t moved = 0;
};

Outcome run(const EdgeCase& c, int threads, bool fused) {
    GrowerConfig cfg;
    cfg.mu = 0.012;
    const CubeIndex index(c.points, cfg.mu, {}, 1);
    const auto n = static_cast<std::uint32_t>(index.size());
    const auto orig = index.original_indices();
    std::vector<std::int32_t> labels(n + CubeIndex::kPadding, -1);
    for (std::uint32_t i = 0; i < n; ++i) labels[i] = c.grown[orig[i]];
    detail::SensorSight sight;
    sight.origins = {index.to_local(Vec3d(-0.3, 0, 0.3))};
    if (fused) sight.origins.push_back(index.to_local(Vec3d(-0.3, 0.1, 0.3)));
    sight.named = true;
    sight.scan_index = c.scan;
    sight.original = orig;
    EXPECT_EQ(sight.fused(), fused);
    const NoiseProfile noise, layers;
    std::vector<float> distance(n, 0.f);
    const detail::GrowContext ctx{
        index, cfg, std::span<std::int32_t>(labels.data(), n), distance, sight, noise, layers};
    // Several slabs, so that the cubes along the edge fall into different ones.
    const auto cubes = static_cast<std::uint32_t>(index.cube_count());
    std::vector<detail::Slab> slabs;
    for (std::uint32_t k = 0; k < 4; ++k) slabs.push_back({k * cubes / 4, (k + 1) * cubes / 4});
    Outcome out;
    out.moved = detail::reassign_at_edges(ctx, slabs, c.surfaces, c.tolerance, threads,
                                          std::span<std::int32_t>(labels.data(), n));
    out.labels.assign(n, -1);
    for (std::uint32_t i = 0; i < n; ++i) out.labels[orig[i]] = labels[i];
    return out;
}

TEST(EdgePass, PointsTakenAcrossAnEdgeGoBackToTheirFaceInTheirScansLayer) {
    const EdgeCase c;
    const Outcome o = run(c, 1, true);
    std::uint64_t taken = 0;
    for (std::size_t k = 0; k < c.points.size(); ++k) {
        if (c.part[k] == EdgeCase::kWall) {
            EXPECT_EQ(o.labels[k], 2) << k;  // the wall's points stay on the wall
            continue;
        }
        if (c.grown[k] == 2) {
            ++taken;
            EXPECT_TRUE(o.labels[k] == 0 || o.labels[k] == 1) << k;  // back to the floor
        } else {
            EXPECT_EQ(o.labels[k], c.grown[k]) << k;  // no move between coplanar surfaces
        }
    }
    ASSERT_GT(taken, 50u);
    EXPECT_EQ(o.moved, taken);
}

TEST(EdgePass, TheSameForAnyThreadCount) {
    const EdgeCase c;
    const Outcome one = run(c, 1, true);
    for (const int threads : {2, 3}) {
        const Outcome o = run(c, threads, true);
        EXPECT_EQ(o.labels, one.labels) << threads << " threads";
        EXPECT_EQ(o.moved, one.moved);
    }
}

TEST(EdgePass, LeavesASingleScanAlone) {
    // One scan has one layer: the shifted planes are the planes, which best fit already used.
    const EdgeCase c;
    const Outcome o = run(c, 2, false);
    EXPECT_EQ(o.moved, 0u);
    EXPECT_EQ(o.labels, c.grown);
}

}  // namespace
}  // namespace surfgrow
