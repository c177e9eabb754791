#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "support/test_support.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/error.hpp"

namespace surfgrow {
namespace {

std::vector<std::uint32_t> brute_force(const std::vector<Vec3f>& pts, const CubeIndex& index,
                                       std::uint32_t q_sorted, float radius) {
    // Same arithmetic as the index: local float coordinates.
    const Vec3f q = index.local_point(q_sorted);
    std::vector<std::uint32_t> out;
    for (std::uint32_t i = 0; i < index.size(); ++i) {
        const Vec3f d = index.local_point(i) - q;
        if (d.x() * d.x() + d.y() * d.y() + d.z() * d.z() <= radius * radius) out.push_back(i);
    }
    (void)pts;
    return out;
}

std::vector<std::uint32_t> via_table(const CubeIndex& index, std::uint32_t q_sorted, float radius) {
    std::vector<CubeIndex::Range> table;
    const std::uint32_t c = index.cube_of(q_sorted);
    index.neighbour_table(c, c + 1, table);
    const Vec3f q = index.local_point(q_sorted);
    std::vector<std::uint32_t> out;
    for (const auto& r : table) {
        for (std::uint32_t i = r.begin; i < r.end; ++i) {
            const Vec3f d = index.local_point(i) - q;
            if (d.x() * d.x() + d.y() * d.y() + d.z() * d.z() <= radius * radius) out.push_back(i);
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::uint32_t> via_query(const CubeIndex& index, std::uint32_t q_sorted,
                                     double radius) {
    std::vector<std::uint32_t> out;
    index.for_each_within(index.world_point(q_sorted), radius,
                          [&](std::uint32_t i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
}

// Every point's neighbourhood, found three ways, must agree with brute force.
void check_all_queries(const std::vector<Vec3f>& pts, double mu) {
    const CubeIndex index(pts, mu);
    ASSERT_EQ(index.size(), pts.size());
    const auto r = static_cast<float>(mu);
    for (std::uint32_t q = 0; q < index.size(); ++q) {
        const auto expected = brute_force(pts, index, q, r);
        ASSERT_EQ(via_table(index, q, r), expected) << "table, point " << q;
        ASSERT_EQ(via_query(index, q, mu), expected) << "query, point " << q;
    }
}

TEST(CubeIndex, RandomCloudMatchesBruteForce) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-0.1f, 0.1f);
    std::vector<Vec3f> pts(3000);
    for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
    check_all_queries(pts, 0.012);
}

TEST(CubeIndex, PointsExactlyOnCubeBorders) {
    // A lattice at exactly the cube spacing puts every point on a border, and neighbours at
    // exactly mu: the query must include them (distance <= mu).
    const double mu = 0.01;
    std::vector<Vec3f> pts;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (int k = 0; k < 4; ++k)
                pts.emplace_back(float(i * mu), float(j * mu), float(k * mu));
    check_all_queries(pts, mu);
    // The same lattice on the index's own (slightly enlarged) cube borders.
    const CubeIndex probe(pts, mu);
    std::vector<Vec3f> on_borders;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            on_borders.emplace_back(float(i * probe.cube_size()), float(j * probe.cube_size()),
                                    0.f);
    check_all_queries(on_borders, mu);
}

TEST(CubeIndex, FarApartClustersStaySparse) {
    // Two clusters 10 km apart at mu = 12 mm: no dense grid could hold this.
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0.f, 0.05f);
    std::vector<Vec3f> pts;
    for (int i = 0; i < 500; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
    for (int i = 0; i < 500; ++i)
        pts.emplace_back(10000.f + u(rng), -5000.f + u(rng), 300.f + u(rng));
    const CubeIndex index(pts, 0.012);
    EXPECT_LE(index.cube_count(), pts.size());
    EXPECT_GE(index.key_bits().sum(), 40);
    for (std::uint32_t q = 0; q < index.size(); q += 7) {
        const auto expected = brute_force(pts, index, q, 0.012f);
        ASSERT_EQ(via_query(index, q, 0.012), expected);
        ASSERT_EQ(via_table(index, q, 0.012f), expected);
    }
}

TEST(CubeIndex, LargeRadiusQueriesMatchBruteForce) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.f, 0.2f);
    std::vector<Vec3f> pts(2000);
    for (auto& p : pts) p = {u(rng), u(rng), u(rng) * 0.1f};
    const CubeIndex index(pts, 0.01);
    for (double radius : {0.005, 0.01, 0.025, 0.047}) {
        for (std::uint32_t q = 0; q < index.size(); q += 13) {
            ASSERT_EQ(via_query(index, q, radius),
                      brute_force(pts, index, q, static_cast<float>(radius)))
                << "radius " << radius;
        }
    }
}

TEST(CubeIndex, CubesHoldTheirPointsContiguously) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    std::vector<Vec3f> pts(5000);
    for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
    const CubeIndex index(pts, 0.1, {}, 2);
    std::set<std::uint32_t> seen;
    for (std::size_t c = 0; c < index.cube_count(); ++c) {
        if (c > 0) {
            EXPECT_LT(index.cube_key(c - 1), index.cube_key(c));
        }
        for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
            EXPECT_EQ(index.coords_of(index.local_point(i)), index.cube_coords(c));
            EXPECT_EQ(index.cube_of(i), c);
            // The ranged search, over a few cubes either side (as a slab's growing uses it).
            const auto cc = static_cast<std::uint32_t>(c);
            const auto last = static_cast<std::uint32_t>(std::min(c + 4, index.cube_count()));
            EXPECT_EQ(index.cube_of(i, cc > 2 ? cc - 2 : 0, last), c);
            EXPECT_EQ(index.cube_of(i, cc, cc + 1), c);
            // Sorted coordinates are the input's, less the origin.
            const Vec3d w = index.world_point(i);
            EXPECT_NEAR((w - pts[index.original_indices()[i]].cast<double>()).norm(), 0.0, 1e-6);
            seen.insert(index.original_indices()[i]);
        }
    }
    EXPECT_EQ(seen.size(), pts.size());
}

TEST(CubeIndex, SameIndexForAnyThreadCount) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-3.f, 3.f);
    std::vector<Vec3f> pts(150000);
    for (auto& p : pts) p = {u(rng), u(rng), u(rng) * 0.2f};
    const CubeIndex a(pts, 0.012, {}, 1), b(pts, 0.012, {}, 2), c(pts, 0.012, {}, 4);
    ASSERT_EQ(a.cube_count(), b.cube_count());
    ASSERT_TRUE(std::equal(a.original_indices().begin(), a.original_indices().end(),
                           b.original_indices().begin()));
    ASSERT_TRUE(std::equal(a.original_indices().begin(), a.original_indices().end(),
                           c.original_indices().begin()));
}

TEST(CubeIndex, SkipsNonFiniteAndExcludedPoints) {
    const float nan = std::nanf(""), inf = INFINITY;
    std::vector<Vec3f> pts = {{0, 0, 0},   {nan, 0, 0},    {0.001f, 0, 0},
                              {0, inf, 0}, {0.002f, 0, 0}, {0, 0, -inf}};
    std::vector<std::uint8_t> include = {1, 1, 0, 1, 1, 1};
    const CubeIndex index(pts, 0.01, include);
    ASSERT_EQ(index.size(), 2u);
    std::set<std::uint32_t> kept(index.original_indices().begin(), index.original_indices().end());
    EXPECT_EQ(kept, (std::set<std::uint32_t>{0, 4}));
}

TEST(CubeIndex, EmptyAndAllInvalidClouds) {
    const CubeIndex empty(std::vector<Vec3f>{}, 0.01);
    EXPECT_EQ(empty.size(), 0u);
    EXPECT_EQ(empty.cube_count(), 0u);
    int calls = 0;
    empty.for_each_within(Vec3d::Zero(), 1.0, [&](std::uint32_t) { ++calls; });
    EXPECT_EQ(calls, 0);
    const CubeIndex nans(std::vector<Vec3f>(10, Vec3f::Constant(std::nanf(""))), 0.01);
    EXPECT_EQ(nans.size(), 0u);
}

TEST(CubeIndex, RejectsBadCubeSize) {
    const std::vector<Vec3f> pts = {{0, 0, 0}, {1, 1, 1}};
    for (double bad : {0.0, -1.0, std::nan(""), double(INFINITY)}) {
        try {
            const CubeIndex index(pts, bad);
            FAIL() << "accepted cube size " << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
        }
    }
}

// The grid coordinates of sorted point i, from its local coordinates alone (not the keys).
Vec3d grid_of(const CubeIndex& index, std::uint32_t i) {
    return (index.local_point(i).cast<double>() / index.cube_size()).array().floor();
}

// The points of the 27 cubes around every cube, by brute force over all points, against the
// neighbour table and the column runs; then radius queries of one and of 2.5 cubes.
void check_against_brute_force(const std::vector<Vec3f>& pts, double mu) {
    const CubeIndex index(pts, mu);
    ASSERT_EQ(index.size(), pts.size());
    std::vector<CubeIndex::Range> table, runs;
    for (std::size_t c = 0; c < index.cube_count(); ++c) {
        const Vec3d g = index.grid_coords(c);
        std::vector<std::uint32_t> expected, from_table, from_runs;
        for (std::uint32_t i = 0; i < index.size(); ++i) {
            const Vec3d d = grid_of(index, i) - g;
            if (d.cwiseAbs().maxCoeff() <= 1) expected.push_back(i);
            if (i >= index.cube_begin(c) && i < index.cube_end(c)) {
                ASSERT_EQ(grid_of(index, i), g);
            }
        }
        index.neighbour_table(c, c + 1, table);
        runs.clear();
        index.column_ranges(index.cube_coords(c), 1, runs);
        for (const auto& r : table)
            for (std::uint32_t i = r.begin; i < r.end; ++i) from_table.push_back(i);
        for (const auto& r : runs)
            for (std::uint32_t i = r.begin; i < r.end; ++i) from_runs.push_back(i);
        std::sort(from_table.begin(), from_table.end());
        ASSERT_EQ(from_table, expected) << "table, cube " << c;
        ASSERT_EQ(from_runs, expected) << "runs, cube " << c;  // already in sorted order
        // The same columns as cube numbers.
        std::vector<CubeIndex::Range> cube_runs;
        index.column_cube_ranges(index.cube_coords(c), 1, cube_runs);
        ASSERT_EQ(cube_runs.size(), runs.size());
        for (std::size_t k = 0; k < runs.size(); ++k) {
            ASSERT_EQ(index.cube_begin(cube_runs[k].begin), runs[k].begin);
            ASSERT_EQ(index.cube_begin(cube_runs[k].end), runs[k].end);
        }
    }
    for (double radius : {mu, 2.5 * mu})
        for (std::uint32_t q = 0; q < index.size(); ++q)
            ASSERT_EQ(via_query(index, q, radius),
                      brute_force(pts, index, q, static_cast<float>(radius)))
                << "query of radius " << radius << ", point " << q;
}

TEST(CubeIndex, AnExtentOf1e7MetresMatchesBruteForce) {
    // Lattice clusters at the corners and the middle of a 1e7 m cube, 1 m steps (the float
    // resolution there), 4 m cubes: grid keys would need 3 x 22 bits.
    std::vector<Vec3f> pts;
    const double far = 1e7;
    std::uint64_t seed = 1;
    for (const Vec3d& base :
         {Vec3d(0, 0, 0), Vec3d(far, far, far), Vec3d(far, 0, far / 2), Vec3d(0.3 * far, far, 0)})
        test::lattice_patches(1.0, base, seed++, pts);
    // Cubes one apart and two apart along each axis beside the first cluster.
    for (float k : {100.f, 104.f, 112.f, 116.f, 124.f}) {
        pts.emplace_back(k, -50.f, -50.f);
        pts.emplace_back(-50.f, k, -50.f);
        pts.emplace_back(-50.f, -50.f, k);
    }
    const CubeIndex index(pts, 4.0);
    EXPECT_TRUE(index.ranked());
    EXPECT_LE(index.key_bits().sum(), 63);
    check_against_brute_force(pts, 4.0);
}

TEST(CubeIndex, ClustersAMillionMetresApartMatchBruteForce) {
    // Two lattice clusters of 1/16 m steps (exact floats up to 2^20 m), 1e6 m apart on each
    // axis, with 0.25 m cubes: grid keys would need 3 x 22 bits.
    std::vector<Vec3f> pts;
    test::lattice_patches(1.0 / 16, Vec3d::Zero(), 1, pts);
    test::lattice_patches(1.0 / 16, Vec3d::Constant(1e6), 2, pts);
    const double mu = test::mu_for_cube_side(0.25);
    EXPECT_TRUE(CubeIndex(pts, mu).ranked());
    check_against_brute_force(pts, mu);
    // The near cluster alone, packed: the same cubes, points and runs in the same order.
    const std::vector<Vec3f> near(pts.begin(),
                                  pts.begin() + static_cast<std::ptrdiff_t>(pts.size() / 2));
    const CubeIndex both(pts, mu), alone(near, mu);
    EXPECT_FALSE(alone.ranked());
    std::vector<CubeIndex::Range> t_both, t_alone;
    both.neighbour_table(0, alone.cube_count(), t_both);
    alone.neighbour_table(0, alone.cube_count(), t_alone);
    for (std::size_t c = 0; c < alone.cube_count(); ++c) {
        EXPECT_EQ(both.grid_coords(c), alone.grid_coords(c));
        EXPECT_EQ(both.cube_begin(c), alone.cube_begin(c));
    }
    for (std::size_t k = 0; k < t_alone.size(); ++k)
        if (t_alone[k].begin < t_alone[k].end) {
            EXPECT_EQ(t_both[k].begin, t_alone[k].begin);
            EXPECT_EQ(t_both[k].end, t_alone[k].end);
        }
}

// Column runs of wide reach on a packed (unranked) index, where most columns around a surface
// are empty, against brute force: every point within `reach` cubes on each axis, in sorted
// order, no empty run, and the same columns as cube numbers.
TEST(CubeIndex, WideColumnRunsMatchBruteForce) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    std::vector<Vec3f> pts;
    for (int k = 0; k < 1500; ++k) {  // a wall, a tilted floor and loose points
        pts.emplace_back(0.3f, u(rng), u(rng));
        const float x = u(rng), y = u(rng);
        pts.emplace_back(x, y, 0.2f * x + 0.1f);
        if (k % 10 == 0) pts.emplace_back(u(rng), u(rng), u(rng));
    }
    const double mu = 0.04;
    const CubeIndex index(pts, mu);
    ASSERT_FALSE(index.ranked());
    std::vector<CubeIndex::Range> runs, cube_runs;
    for (const int reach : {0, 1, 2, 3, 7}) {
        for (std::size_t c = 0; c < index.cube_count(); c += 3) {
            const Vec3d g = index.grid_coords(c);
            std::vector<std::uint32_t> expected, from_runs;
            for (std::uint32_t i = 0; i < index.size(); ++i)
                if ((grid_of(index, i) - g).cwiseAbs().maxCoeff() <= reach) expected.push_back(i);
            runs.clear();
            cube_runs.clear();
            index.column_ranges(index.cube_coords(c), reach, runs);
            index.column_cube_ranges(index.cube_coords(c), reach, cube_runs);
            for (const auto& r : runs) {
                ASSERT_LT(r.begin, r.end) << "an empty run";
                for (std::uint32_t i = r.begin; i < r.end; ++i) from_runs.push_back(i);
            }
            ASSERT_EQ(from_runs, expected) << "reach " << reach << ", cube " << c;
            ASSERT_EQ(cube_runs.size(), runs.size());
            for (std::size_t k = 0; k < runs.size(); ++k) {
                ASSERT_EQ(index.cube_begin(cube_runs[k].begin), runs[k].begin);
                ASSERT_EQ(index.cube_begin(cube_runs[k].end), runs[k].end);
            }
        }
    }
}

TEST(CubeIndex, RanksKeepNeighboursAndGaps) {
    // Cubes g, g + 1, g + 3 and g + 6 along x (ranks 1, 2, 4, 6), made ranked by a far point:
    // g + 1 and g + 3 must not become neighbours, nor g + 3 and g + 6.
    std::vector<Vec3f> pts = {
        {0.5f, 0, 0}, {1.5f, 0, 0}, {3.5f, 0, 0}, {6.5f, 0, 0}, {1e30f, 1e30f, 1e30f}};
    const CubeIndex index(pts, 1.0);
    ASSERT_TRUE(index.ranked());
    ASSERT_EQ(index.cube_count(), 5u);
    std::vector<CubeIndex::Range> table;
    index.neighbour_table(0, 4, table);
    auto neighbours = [&](std::size_t c) {
        std::vector<std::uint32_t> out;
        for (std::size_t k = 0; k < 9; ++k)
            for (std::uint32_t i = table[9 * c + k].begin; i < table[9 * c + k].end; ++i)
                out.push_back(index.original_indices()[i]);
        std::sort(out.begin(), out.end());
        return out;
    };
    EXPECT_EQ(neighbours(0), (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(neighbours(1), (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(neighbours(2), (std::vector<std::uint32_t>{2}));
    EXPECT_EQ(neighbours(3), (std::vector<std::uint32_t>{3}));
    // Queries from empty cubes and of several cubes' reach see through the ranks to the grid.
    const Vec3d p0 = index.world_point(0);
    auto near = [&](double dx, double radius) {
        std::vector<std::uint32_t> out;
        index.for_each_within(p0 + Vec3d(dx, 0, 0), radius,
                              [&](std::uint32_t i) { out.push_back(index.original_indices()[i]); });
        std::sort(out.begin(), out.end());
        return out;
    };
    EXPECT_EQ(near(4.5, 0.6), (std::vector<std::uint32_t>{}));  // in the empty cube g + 4
    EXPECT_EQ(near(4.5, 1.6), (std::vector<std::uint32_t>{2, 3}));
    EXPECT_EQ(near(0.0, 3.0), (std::vector<std::uint32_t>{0, 1, 2}));  // reach of 3 cubes
    EXPECT_EQ(index.grid_coords(3).x() - index.grid_coords(0).x(), 6.0);
}

TEST(CubeIndex, AnyFiniteExtentWithinFloatRange) {
    // 1e30 m apart at 12 mm cubes (1e32 cubes): indexed by ranks, each point its own neighbour.
    const std::vector<Vec3f> huge = {{-1e30f, 0, 0}, {1e30f, 1e30f, 1e30f}, {0, 0, 0}};
    const CubeIndex index(huge, 0.012);
    EXPECT_TRUE(index.ranked());
    EXPECT_EQ(index.cube_count(), 3u);
    for (std::uint32_t q = 0; q < index.size(); ++q)
        EXPECT_EQ(via_query(index, q, 0.012), std::vector<std::uint32_t>{q});
    // Beyond float range the local coordinates cannot be floats: refused, with a way out.
    const std::vector<Vec3f> beyond = {{-3e38f, 0, 0}, {3e38f, 0, 0}};
    try {
        const CubeIndex refused(beyond, 0.012);
        FAIL() << "indexed a 6e38 extent";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
        EXPECT_NE(std::string(e.what()).find("crop"), std::string::npos);
    }
}

TEST(CubeIndex, QueryFarOutsideTheCloudFindsNothing) {
    const std::vector<Vec3f> pts = {{0, 0, 0}, {0.001f, 0, 0}};
    const CubeIndex index(pts, 0.01);
    int calls = 0;
    index.for_each_within(Vec3d(1e12, -1e12, 5), 0.01, [&](std::uint32_t) { ++calls; });
    EXPECT_EQ(calls, 0);
    index.for_each_within(Vec3d(0, 0, 0), 0.0005, [&](std::uint32_t) { ++calls; });
    EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace surfgrow
