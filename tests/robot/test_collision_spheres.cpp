// Collision spheres against brute force: random environments, random spheres and capsules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "surfgrow/core/error.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/robot_model.hpp"

namespace surfgrow {
namespace {

Proximity brute_nearest(const std::vector<Sphere>& env, const Capsule& q) {
    Proximity best;
    for (std::size_t i = 0; i < env.size(); ++i) {
        const double d = clearance(env[i], q);
        if (d < best.clearance) {  // strict: the lowest id wins ties
            best.clearance = d;
            best.nearest = static_cast<std::int64_t>(i);
        }
    }
    return best;
}

std::vector<std::uint32_t> brute_colliding(const std::vector<Sphere>& env, const Capsule& q,
                                           double tol) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < env.size(); ++i)
        if (clearance(env[i], q) < tol) out.push_back(static_cast<std::uint32_t>(i));
    return out;
}

constexpr double kEps = 1e-12;

// Whether a sphere other than the nearest is within kEps of the nearest's clearance.
bool near_tie(const std::vector<Sphere>& env, const Capsule& q, const Proximity& best) {
    for (std::size_t i = 0; i < env.size(); ++i)
        if (std::int64_t(i) != best.nearest && clearance(env[i], q) - best.clearance < kEps)
            return true;
    return false;
}

// Whether a sphere's clearance is within kEps of the tolerance (the answer hangs on rounding).
bool near_tolerance(const std::vector<Sphere>& env, const Capsule& q, double tol) {
    for (const Sphere& s : env)
        if (std::abs(clearance(s, q) - tol) < kEps) return true;
    return false;
}

// Spheres on a few noisy planes (like home points) plus a scattered cloud, radii around mu.
std::vector<Sphere> random_environment(std::size_t n, std::mt19937_64& rng, bool varied_radii) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_real_distribution<double> r(0.006, 0.048);
    std::vector<Sphere> env(n);
    for (std::size_t i = 0; i < n; ++i) {
        Vec3d c(u(rng), u(rng), u(rng));
        if (i % 3 == 0) c.z() = 0.01 * u(rng);        // a floor
        if (i % 3 == 1) c.x() = 0.8 + 0.01 * u(rng);  // a wall
        env[i] = {c, varied_radii ? r(rng) : 0.012};
    }
    return env;
}

Capsule random_query(std::mt19937_64& rng, int kind) {
    std::uniform_real_distribution<double> u(-1.3, 1.3);
    std::uniform_real_distribution<double> len(0.0, 0.6);
    std::uniform_real_distribution<double> rad(0.0, 0.15);
    const Vec3d a(u(rng), u(rng), u(rng));
    if (kind == 0) return {a, a, rad(rng)};  // sphere
    Vec3d dir(u(rng), u(rng), u(rng));
    dir.normalize();
    if (kind == 2) dir = Vec3d::UnitX();  // axis-aligned, parallel to the floor
    return {a, a + len(rng) * dir, rad(rng)};
}

void check_environment(const std::vector<Sphere>& env, std::uint64_t seed, int queries) {
    const CollisionSpheres spheres(env);
    ASSERT_EQ(spheres.size(), env.size());
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> tol(-0.05, 0.1);
    for (int i = 0; i < queries; ++i) {
        const Capsule q = random_query(rng, i % 3);
        const Proximity want = brute_nearest(env, q);
        const Proximity got = spheres.nearest(q);
        // The same formula inlined in two places may round differently in the last bit (FMA):
        // equal to 1e-12, and the id is the brute-force one unless another is as near.
        ASSERT_NEAR(got.clearance, want.clearance, kEps) << "query " << i;
        ASSERT_GE(got.nearest, 0);
        ASSERT_NEAR(clearance(env[std::size_t(got.nearest)], q), want.clearance, kEps);
        if (!near_tie(env, q, want)) {
            ASSERT_EQ(got.nearest, want.nearest) << "query " << i;
        }
        if (q.a == q.b) {
            const Proximity as_sphere = spheres.nearest(Sphere{q.a, q.radius});
            ASSERT_EQ(as_sphere.nearest, got.nearest);
            ASSERT_EQ(spheres.min_distance(Sphere{q.a, q.radius}), got.clearance);
        }
        const double t = tol(rng);
        if (near_tolerance(env, q, t)) continue;
        const std::vector<std::uint32_t> hits = brute_colliding(env, q, t);
        ASSERT_EQ(spheres.collides(q, t), !hits.empty()) << "query " << i;
        ASSERT_EQ(spheres.colliding(q, t), hits) << "query " << i;
        if (std::abs(want.clearance) > kEps) {
            ASSERT_EQ(spheres.collides(q), want.clearance < 0);
        }
    }
}

TEST(CollisionSpheres, NearestAndCollidesMatchBruteForce) {
    std::mt19937_64 rng(1);
    for (const std::size_t n : {1u, 2u, 3u, 5u, 17u, 300u, 5000u}) {
        check_environment(random_environment(n, rng, false), n, n > 1000 ? 600 : 2000);
        check_environment(random_environment(n, rng, true), n + 1, n > 1000 ? 600 : 2000);
    }
}

TEST(CollisionSpheres, TiesGoToTheLowestIdAndDuplicatesAreFine) {
    // Eight copies of the same sphere, and a ring of spheres at the same distance from the query.
    std::vector<Sphere> env(8, Sphere{{1, 1, 1}, 0.1});
    for (int k = 0; k < 12; ++k) {
        const double a = 2 * M_PI * k / 12;
        env.push_back({{3 + std::cos(a), 3 + std::sin(a), 0}, 0.1});
    }
    check_environment(env, 3, 500);
    const CollisionSpheres spheres(env);
    EXPECT_EQ(spheres.nearest(Sphere{{1, 1, 2}, 0.0}).nearest, 0);
    const Proximity p = spheres.nearest(Sphere{{3, 3, 0}, 0.0});
    EXPECT_GE(p.nearest, 8);
    EXPECT_NEAR(p.clearance, 0.9, 1e-12);
}

TEST(CollisionSpheres, KnownAnswers) {
    const CollisionSpheres env({{{0, 0, 0}, 0.012}, {{1, 0, 0}, 0.012}});
    // A sphere 0.5 m above the first: clearance 0.5 - 0.012 - 0.1.
    Proximity p = env.nearest(Sphere{{0, 0, 0.5}, 0.1});
    EXPECT_EQ(p.nearest, 0);
    EXPECT_NEAR(p.clearance, 0.388, 1e-12);
    // Penetration: negative clearance by the overlap depth.
    p = env.nearest(Sphere{{1, 0, 0.05}, 0.05});
    EXPECT_EQ(p.nearest, 1);
    EXPECT_NEAR(p.clearance, -0.012, 1e-12);
    EXPECT_TRUE(env.collides(Sphere{{1, 0, 0.05}, 0.05}));
    // A capsule over both: its segment runs 0.2 above them, closest at the segment's interior.
    const Capsule c{{-0.5, 0, 0.2}, {1.5, 0, 0.2}, 0.05};
    EXPECT_NEAR(env.min_distance(c), 0.2 - 0.012 - 0.05, 1e-12);
    EXPECT_FALSE(env.collides(c));
    EXPECT_TRUE(env.collides(c, 0.2));     // a 20 cm margin is not kept
    EXPECT_FALSE(env.collides(c, 0.138));  // exactly the clearance: clear (clearance < tolerance)
    // Past the segment's end: distance to the end point.
    const Capsule end{{2, 0, 0}, {3, 0, 0}, 0.0};
    EXPECT_NEAR(env.min_distance(end), 1 - 0.012, 1e-12);
    // A degenerate capsule (a == b) is a sphere.
    EXPECT_EQ(env.min_distance(Capsule{{0, 0, 1}, {0, 0, 1}, 0.1}),
              env.min_distance(Sphere{{0, 0, 1}, 0.1}));
}

TEST(CollisionSpheres, EmptyEnvironment) {
    const CollisionSpheres env;
    const Proximity p = env.nearest(Sphere{{0, 0, 0}, 1.0});
    EXPECT_EQ(p.nearest, -1);
    EXPECT_EQ(p.clearance, std::numeric_limits<double>::infinity());
    EXPECT_FALSE(env.collides(Capsule{{0, 0, 0}, {1, 1, 1}, 1.0}, 100.0));
    EXPECT_TRUE(env.colliding(Capsule{{0, 0, 0}, {1, 1, 1}, 1.0}, 100.0).empty());
    const CollisionSpheres from_none = CollisionSpheres::from_surfaces({});
    EXPECT_TRUE(from_none.empty());
}

TEST(CollisionSpheres, FromSurfacesUsesHomePointsAndRadii) {
    std::vector<Surface> surfaces(3);
    surfaces[0].home = {0, 0, 0};
    surfaces[0].radius = 0.012;
    surfaces[1].home = {0.1, 0, 0};
    surfaces[1].radius = 0.024;
    surfaces[2].home = {0.2, 0, 0};
    surfaces[2].radius = 0.012;
    const CollisionSpheres env = CollisionSpheres::from_surfaces(surfaces);
    ASSERT_EQ(env.size(), 3u);
    EXPECT_EQ(env.spheres()[1].centre, surfaces[1].home);
    EXPECT_EQ(env.max_radius(), 0.024);
    const Proximity p = env.nearest(Sphere{{0.1, 0.1, 0}, 0.0});
    EXPECT_EQ(p.nearest, 1);
    EXPECT_NEAR(p.clearance, 0.1 - 0.024, 1e-12);
}

TEST(CollisionSpheres, BadShapesAreErrorsNotCrashes) {
    const double nan = std::nan("");
    const double inf = std::numeric_limits<double>::infinity();
    auto code = [](auto&& f) {
        try {
            f();
        } catch (const Error& e) {
            return e.code();
        }
        return ErrorCode::kInternal;
    };
    for (const Sphere& bad : {Sphere{{0, 0, 0}, -1.0}, Sphere{{nan, 0, 0}, 1.0},
                              Sphere{{0, 0, 0}, nan}, Sphere{{0, inf, 0}, 1.0}}) {
        EXPECT_EQ(code([&] { CollisionSpheres env({bad}); }), ErrorCode::kInvalidParameter);
        const CollisionSpheres env({{{0, 0, 0}, 0.1}});
        EXPECT_EQ(code([&] { (void)env.nearest(bad); }), ErrorCode::kInvalidParameter);
        EXPECT_EQ(code([&] { (void)env.collides(bad); }), ErrorCode::kInvalidParameter);
    }
    const CollisionSpheres env({{{0, 0, 0}, 0.1}});
    EXPECT_EQ(code([&] {
                  (void)env.collides(Capsule{{0, 0, 0}, {nan, 0, 0}, 0.1});
              }),
              ErrorCode::kInvalidParameter);
    EXPECT_EQ(code([&] {
                  (void)env.collides(Sphere{{0, 0, 0}, 0.1}, nan);
              }),
              ErrorCode::kInvalidParameter);
    // A zero radius is a point: allowed.
    EXPECT_NEAR(env.min_distance(Sphere{{1, 0, 0}, 0.0}), 0.9, 1e-12);
}

TEST(CollisionSpheres, TreeStaysShallowOnDegenerateInput) {
    // Every centre on one line, and every centre equal: median splits keep the depth logarithmic.
    std::vector<Sphere> line, same;
    for (int i = 0; i < 100000; ++i) {
        line.push_back({{i * 1e-3, 0, 0}, 0.01});
        same.push_back({{0.5, 0.5, 0.5}, 0.01});
    }
    EXPECT_LE(CollisionSpheres(line).depth(), 18);
    const CollisionSpheres s(same);
    EXPECT_LE(s.depth(), 18);
    EXPECT_EQ(s.nearest(Sphere{{0, 0, 0}, 0.0}).nearest, 0);
}

TEST(RobotModel, PerLinkClearanceAndCollision) {
    const CollisionSpheres env({{{0, 0, 0}, 0.012}, {{1, 0, 0}, 0.012}});
    RobotModel robot;
    robot.links.push_back({"base", RobotLink::Kind::kSphere, {{0, 0, 0.5}, {0, 0, 0.5}, 0.1}});
    robot.links.push_back({"arm", RobotLink::Kind::kCapsule, {{0.5, 0, 0.5}, {1, 0, 0.03}, 0.02}});
    const std::vector<LinkClearance> r = check_robot(env, robot, 0.005);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].proximity.nearest, 0);
    EXPECT_NEAR(r[0].proximity.clearance, 0.388, 1e-12);
    EXPECT_FALSE(r[0].collides);
    EXPECT_EQ(r[1].proximity.nearest, 1);
    EXPECT_NEAR(r[1].proximity.clearance, 0.03 - 0.012 - 0.02, 1e-12);
    EXPECT_TRUE(r[1].collides);
    robot.links[1].shape.radius = -1;
    EXPECT_THROW((void)check_robot(env, robot, 0.0), Error);
    EXPECT_THROW((void)check_robot(env, {}, std::nan("")), Error);
    EXPECT_TRUE(check_robot(env, {}, 0.0).empty());
}

}  // namespace
}  // namespace surfgrow
