// Coverage goals, sweep order and approach poses on analytic planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/robot/coverage.hpp"

namespace surfgrow {
namespace {

constexpr double kDeg = M_PI / 180.0;
const std::span<const Surface> kNoSurfaces;

// A rectangular plane of w x h around `centre`, with the given frame.
BoundPlane rect_plane(const Vec3d& centre, const Vec3d& normal, const Vec3d& u, double w,
                      double h) {
    BoundPlane p;
    p.centroid = centre;
    p.normal = normal;
    p.u_axis = u;
    p.v_axis = normal.cross(u);
    p.polygons = {{{{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}}, {}}};
    p.area = w * h;
    return p;
}

BoundPlanes planes_of(std::vector<BoundPlane> list) {
    BoundPlanes p;
    p.config.mu = 0.012;
    for (const BoundPlane& bp : list) p.stats.area += bp.area;
    p.planes = std::move(list);
    return p;
}

// A floor and a wall meeting at an edge, as in a room corner, and a plate with a hole.
BoundPlanes corner() {
    BoundPlane floor = rect_plane({0.2, 0.15, 0}, Vec3d::UnitZ(), Vec3d::UnitX(), 0.4, 0.3);
    BoundPlane wall = rect_plane({0, 0.15, 0.15}, Vec3d::UnitX(), Vec3d::UnitY(), 0.3, 0.3);
    BoundPlane holed = rect_plane({0.2, 0.5, 0.3}, -Vec3d::UnitY(), Vec3d::UnitX(), 0.2, 0.2);
    holed.polygons[0].holes = {{{-0.03, -0.03}, {-0.03, 0.03}, {0.03, 0.03}, {0.03, -0.03}}};
    holed.area -= 0.06 * 0.06;
    return planes_of({floor, wall, holed});
}

TEST(Coverage, CoversThePlanesWithGoalsOnThem) {
    const BoundPlanes planes = corner();
    const CoveragePlan plan = plan_coverage(planes, kNoSurfaces, CoverageConfig{});
    const CoverageStats& s = plan.stats;
    EXPECT_EQ(plan.config.blast_radius, 0.012);  // mu by default
    EXPECT_EQ(s.planes, 3u);
    EXPECT_EQ(s.transitions, 2u);
    EXPECT_NEAR(s.area, 0.12 + 0.09 + 0.04 - 0.0036, 1e-12);
    // Measured 0.997-0.999: what is left is the outermost strip between grid points.
    EXPECT_GE(s.coverage, 0.99);
    for (const PlaneCoverage& pc : plan.per_plane) EXPECT_GE(pc.covered_fraction, 0.985);
    // A hexagonal covering needs area / (2.6 b^2) discs; greedy filling at the edges adds some.
    const double hex = s.area / (1.5 * std::sqrt(3.0) * 0.012 * 0.012);
    EXPECT_GE(double(s.goals), hex);
    EXPECT_LE(double(s.goals), 1.5 * hex);
    for (const CoverageGoal& g : plan.goals) {
        const BoundPlane& bp = planes.planes[g.plane];
        EXPECT_NEAR(bp.plane().signed_distance(g.position), 0.0, 1e-9);
        // On the plane's area (within the planning grid's half cell of its outline).
        bool near_inside = false;
        for (const Vec2d& d :
             {Vec2d(0, 0), Vec2d(0.003, 0), Vec2d(-0.003, 0), Vec2d(0, 0.003), Vec2d(0, -0.003)})
            near_inside |= polygon_contains(bp.polygons[0], bp.to_plane(g.position) + d);
        EXPECT_TRUE(near_inside) << g.position.transpose();
    }
}

TEST(Coverage, ApproachPosesLieInTheBandAtTheStandoff) {
    CoverageConfig cfg;
    cfg.standoff = 0.25;
    for (const double tilt : {5.0, 22.5, 40.0}) {
        cfg.tilt_deg = tilt;
        const CoveragePlan plan = plan_coverage(corner(), kNoSurfaces, cfg);
        ASSERT_FALSE(plan.goals.empty());
        for (const CoverageGoal& g : plan.goals) {
            EXPECT_NEAR((g.tool_position - g.position).norm(), 0.25, 1e-9);
            EXPECT_NEAR(g.tool_axis.norm(), 1.0, 1e-12);
            // The jet points from the tool to the goal ...
            EXPECT_LT((g.position - g.tool_position).normalized().cross(g.tool_axis).norm(), 1e-9);
            // ... at `tilt` from the normal, leaning forward into the sweep.
            const double angle = angle_between(-g.tool_axis, g.normal) / kDeg;
            EXPECT_NEAR(angle, tilt, 1e-9);
            EXPECT_NEAR(g.tilt_deg, tilt, 1e-9);
            EXPECT_GE(angle, cfg.min_angle_deg - 1e-9);
            EXPECT_LE(angle, cfg.max_angle_deg + 1e-9);
            EXPECT_GT(g.tool_axis.dot(g.direction), 0);
            EXPECT_GT((g.tool_position - g.position).dot(g.normal), 0);  // on the sensor side
            // The orientation carries the tool frame: z = axis, x = sweep direction.
            const Mat3d r = g.orientation.toRotationMatrix();
            EXPECT_LT((r.col(2) - g.tool_axis).norm(), 1e-9);
            EXPECT_GT(r.col(0).dot(g.direction), 0.5);
            EXPECT_GE(g.orientation.w(), 0);
        }
    }
}

TEST(Coverage, SweepsRunRowByRowInAlternatingDirections) {
    const CoveragePlan plan = plan_coverage(corner(), kNoSurfaces, CoverageConfig{});
    std::size_t turns = 0;
    for (std::size_t k = 1; k < plan.goals.size(); ++k) {
        const CoverageGoal &a = plan.goals[k - 1], &b = plan.goals[k];
        if (b.plane != a.plane) {
            EXPECT_TRUE(b.transition);
            continue;
        }
        EXPECT_FALSE(b.transition);
        if (b.row == a.row) {
            EXPECT_EQ(a.direction, b.direction);  // within a row: one way
            EXPECT_GT((b.position - a.position).dot(a.direction), 0);
        } else {
            ++turns;
            EXPECT_EQ(a.direction, -b.direction);  // a new row goes back
            EXPECT_NE(a.row, b.row);
        }
    }
    EXPECT_GT(turns, 10u);
    // Path metrics add up.
    double tool = 0, goal = 0, between = 0;
    std::size_t transitions = 0;
    for (std::size_t k = 1; k < plan.goals.size(); ++k) {
        const double d = (plan.goals[k].tool_position - plan.goals[k - 1].tool_position).norm();
        tool += d;
        goal += (plan.goals[k].position - plan.goals[k - 1].position).norm();
        if (plan.goals[k].transition) {
            between += d;
            ++transitions;
        }
    }
    EXPECT_NEAR(plan.stats.tool_path_length, tool, 1e-9);
    EXPECT_NEAR(plan.stats.goal_path_length, goal, 1e-9);
    EXPECT_NEAR(plan.stats.transition_length, between, 1e-9);
    EXPECT_NEAR(plan.stats.sweep_length + plan.stats.transition_length, tool, 1e-9);
    EXPECT_EQ(transitions, plan.stats.transitions);
    // Per-plane entries index the goal list.
    for (const PlaneCoverage& pc : plan.per_plane)
        for (std::uint32_t k = pc.first_goal; k < pc.first_goal + pc.goals; ++k)
            EXPECT_EQ(plan.goals[k].plane, pc.plane);
}

TEST(Coverage, PlanesAreVisitedInAShortOrder) {
    // Five plates in a row, listed shuffled: the path visits them along the row.
    std::vector<BoundPlane> list;
    for (const int k : {3, 0, 4, 1, 2})
        list.push_back(rect_plane({0.5 * k, 0, 0}, Vec3d::UnitZ(), Vec3d::UnitX(), 0.1, 0.1));
    CoverageConfig cfg;
    cfg.start = Vec3d(-1, 0, 0.3);
    const CoveragePlan plan = plan_coverage(planes_of(list), kNoSurfaces, cfg);
    ASSERT_EQ(plan.per_plane.size(), 5u);
    const std::uint32_t expected[] = {1, 3, 4, 0, 2};  // x = 0, 0.5, 1, 1.5, 2
    for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(plan.per_plane[k].plane, expected[k]);
    EXPECT_LT(plan.stats.transition_length, 4 * 0.5);
}

TEST(Coverage, ThousandsOfPlanesAreEachVisitedOnceInAShortOrder) {
    // A cluttered room gives thousands of small planes (Bobkov's office: 4,455). Here 3,000
    // plates 5 cm wide on a 60 x 50 grid 0.2 m apart, listed in a scrambled order: every plate is
    // visited once, and the moves between them add up to no more than a row-by-row sweep through
    // the plates' centres (2,999 steps of 0.2 m; 490 m measured), although 2-opt stops after a
    // budget of tested moves.
    const int nx = 60, ny = 50, n = nx * ny;
    std::vector<BoundPlane> list;
    for (int k = 0; k < n; ++k) {
        const int cell =
            static_cast<int>((static_cast<long long>(k) * 1237) % n);  // 1237 is coprime to n
        list.push_back(rect_plane({0.2 * (cell % nx), 0.2 * (cell / nx), 0}, Vec3d::UnitZ(),
                                  Vec3d::UnitX(), 0.05, 0.05));
    }
    CoverageConfig cfg;
    cfg.start = Vec3d(-0.2, 0, 0.3);
    const CoveragePlan plan = plan_coverage(planes_of(list), kNoSurfaces, cfg);
    ASSERT_EQ(plan.per_plane.size(), std::size_t(n));
    std::vector<int> seen(std::size_t(n), 0);
    for (const PlaneCoverage& pc : plan.per_plane) ++seen[pc.plane];
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), n);
    EXPECT_EQ(plan.stats.transitions, std::uint64_t(n - 1));
    const double grid_sweep = 0.2 * (n - 1);
    std::printf("%d plates: transitions %.1f m, a sweep of the grid %.1f m\n", n,
                plan.stats.transition_length, grid_sweep);
    EXPECT_LT(plan.stats.transition_length, grid_sweep);
}

TEST(Coverage, LargerBlastRadiusNeedsFewerGoals) {
    CoverageConfig small, large;
    small.blast_radius = 0.012;
    large.blast_radius = 0.036;
    const auto a = plan_coverage(corner(), kNoSurfaces, small);
    const auto b = plan_coverage(corner(), kNoSurfaces, large);
    EXPECT_LT(double(b.stats.goals), double(a.stats.goals) / 5);
    EXPECT_GE(b.stats.coverage, 0.98);
}

TEST(Coverage, HomePointsFillTheEdges) {
    // Where the lattice leaves the outline uncovered, home points on the plane are preferred.
    BoundPlanes planes = corner();
    std::vector<Surface> surfaces;
    for (double x = 0.006; x < 0.4; x += 0.012)
        for (double y = 0.006; y < 0.3; y += 0.012) {
            surfaces.emplace_back();
            surfaces.back().home = Vec3d(x, y, 0);
            planes.planes[0].patches.push_back(std::uint32_t(surfaces.size() - 1));
        }
    const CoveragePlan plan = plan_coverage(planes, surfaces, CoverageConfig{});
    EXPECT_GE(plan.stats.coverage, 0.99);
    std::size_t homes = 0;
    for (const CoverageGoal& g : plan.goals) {
        if (!g.from_home) continue;
        ++homes;
        EXPECT_EQ(g.plane, 0u);
        const Vec3d rel = g.position / 0.006;  // a home point: odd multiples of 6 mm
        EXPECT_NEAR(rel.x(), std::round(rel.x()), 1e-6);
        EXPECT_NEAR(rel.z(), 0.0, 1e-9);
    }
    EXPECT_GE(homes, 1u);
}

TEST(Coverage, SameGoalsForAnyThreadCount) {
    CoverageConfig cfg;
    cfg.threads = 1;
    const CoveragePlan a = plan_coverage(corner(), kNoSurfaces, cfg);
    cfg.threads = 3;
    const CoveragePlan b = plan_coverage(corner(), kNoSurfaces, cfg);
    ASSERT_EQ(a.goals.size(), b.goals.size());
    for (std::size_t k = 0; k < a.goals.size(); ++k) {
        EXPECT_EQ(a.goals[k].position, b.goals[k].position);
        EXPECT_EQ(a.goals[k].tool_position, b.goals[k].tool_position);
        EXPECT_EQ(a.goals[k].orientation.coeffs(), b.goals[k].orientation.coeffs());
    }
    EXPECT_EQ(a.stats.tool_path_length, b.stats.tool_path_length);
}

TEST(Coverage, NoPlanesGiveAnEmptyPlan) {
    const CoveragePlan plan = plan_coverage(planes_of({}), kNoSurfaces, CoverageConfig{});
    EXPECT_TRUE(plan.goals.empty());
    EXPECT_EQ(plan.stats.coverage, 0.0);
    EXPECT_EQ(plan.stats.transitions, 0u);
    // A plane whose outline is smaller than the grid still gets a goal.
    BoundPlane tiny = rect_plane({0, 0, 0}, Vec3d::UnitZ(), Vec3d::UnitX(), 0.001, 0.001);
    const CoveragePlan t = plan_coverage(planes_of({tiny}), kNoSurfaces, CoverageConfig{});
    EXPECT_EQ(t.goals.size(), 1u);
    EXPECT_EQ(t.stats.coverage, 1.0);
}

TEST(Coverage, RefusesBadParameters) {
    const auto with = [](auto set) {
        CoverageConfig c;
        set(c);
        return c;
    };
    for (const CoverageConfig& c :
         {with([](auto& c) { c.blast_radius = -0.01; }), with([](auto& c) { c.standoff = 0; }),
          with([](auto& c) { c.standoff = NAN; }), with([](auto& c) { c.min_angle_deg = 50; }),
          with([](auto& c) { c.max_angle_deg = 90; }), with([](auto& c) { c.min_angle_deg = -1; }),
          with([](auto& c) { c.tilt_deg = 2.0; }), with([](auto& c) { c.tilt_deg = 45.0; }),
          with([](auto& c) {
              c.blast_radius = 0.01;
              c.sample_spacing = 0.02;
          }),
          with([](auto& c) { c.start = Vec3d(0, NAN, 0); }),
          with([](auto& c) { c.threads = -1; })}) {
        try {
            (void)plan_coverage(corner(), kNoSurfaces, c);
            ADD_FAILURE() << "accepted a bad configuration";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << e.what();
        }
    }
    BoundPlanes no_mu = corner();
    no_mu.config.mu = 0;
    EXPECT_THROW((void)plan_coverage(no_mu, kNoSurfaces, CoverageConfig{}), Error);
}

// Lengths beyond float coordinates are refused (1e308 once hung); a blast radius too small for
// the planes is refused before minutes of work (1 um once did, then a bad_alloc in a parallel
// loop ended in std::terminate); a huge one, or a planning grid finer than any raster, is planned
// correctly.
TEST(Coverage, AbsurdLengthsAreRefusedOrPlanned) {
    auto message = [](const CoverageConfig& c) -> std::string {
        try {
            (void)plan_coverage(corner(), kNoSurfaces, c);
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << e.what();
            return e.what();
        }
        return "";
    };
    CoverageConfig c;
    c.blast_radius = 1e308;
    EXPECT_NE(message(c).find("blast radius = 1e+308 is beyond the range of float"),
              std::string::npos);
    c.blast_radius = 1e-6;
    EXPECT_NE(message(c).find("blast radius 1e-06 is too small for planes up to 0.4"),
              std::string::npos)
        << message(c);
    c = {};
    c.standoff = 1e-300;
    EXPECT_NE(message(c).find("standoff = 1e-300 is below the smallest length"), std::string::npos);
    c = {};
    c.start = Vec3d(0, 0, 1e39);
    EXPECT_NE(message(c).find("start position = 1e+39"), std::string::npos);

    c = {};
    c.blast_radius = 1e38;  // one goal covers each plane
    const CoveragePlan huge = plan_coverage(corner(), kNoSurfaces, c);
    EXPECT_EQ(huge.stats.goals, 3u);
    EXPECT_NEAR(huge.stats.coverage, 1.0, 1e-9);
    c = {};
    c.sample_spacing = 1e-30;  // once minutes of work: (blast radius / spacing)^4
    EXPECT_NE(message(c).find("sample spacing 1e-30 is finer than the blast radius / 16"),
              std::string::npos)
        << message(c);
    c.sample_spacing = 0.012 / 16;  // the finest allowed is planned
    const CoveragePlan fine = plan_coverage(corner(), kNoSurfaces, c);
    EXPECT_GT(fine.stats.goals, 3u);
    EXPECT_GT(fine.stats.coverage, 0.9);
}

}  // namespace
}  // namespace surfgrow
