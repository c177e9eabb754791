// Collision spheres: build and query speed with 100 k environment spheres (home points on the
// walls, floor and ceiling of a 4 x 4 x 2.5 m room, about mu apart, as grown from a fused scan).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "surfgrow/robot/collision_spheres.hpp"

namespace surfgrow::bench {
namespace {

std::vector<Sphere> room_spheres(std::size_t n) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0), noise(-0.002, 0.002);
    const Vec3d size(4.0, 4.0, 2.5);
    std::vector<Sphere> s(n);
    for (std::size_t i = 0; i < n; ++i) {
        Vec3d p(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
        const int face = static_cast<int>(i % 6);
        p[face / 2] = (face % 2 ? size[face / 2] : 0.0) + noise(rng);  // onto one of the 6 faces
        s[i] = {p, 0.012};
    }
    return s;
}

const CollisionSpheres& environment() {
    static const CollisionSpheres env(room_spheres(100000));
    return env;
}

// Robot-sized queries anywhere in the room: spheres of 2-10 cm, capsules 0.2-0.5 m long. About a
// tenth of them touch a wall.
std::vector<Capsule> queries(bool capsules, std::size_t n) {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Capsule> q(n);
    for (auto& c : q) {
        const Vec3d a(0.1 + 3.8 * u(rng), 0.1 + 3.8 * u(rng), 0.1 + 2.3 * u(rng));
        Vec3d b = a;
        if (capsules) {
            const Vec3d dir = Vec3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
            b = a + (0.2 + 0.3 * u(rng)) * dir;
        }
        c = {a, b, 0.02 + 0.08 * u(rng)};
    }
    return q;
}

void BM_Build(benchmark::State& state) {
    const std::vector<Sphere> s = room_spheres(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) {
        CollisionSpheres env(s);
        benchmark::DoNotOptimize(env.depth());
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_Build)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_Nearest(benchmark::State& state) {
    const CollisionSpheres& env = environment();
    const std::vector<Capsule> q = queries(state.range(0) != 0, 1 << 16);
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(env.nearest(q[i++ & (q.size() - 1)]));
    }
    state.SetItemsProcessed(state.iterations());
    state.SetLabel(state.range(0) ? "capsule" : "sphere");
}
BENCHMARK(BM_Nearest)->Arg(0)->Arg(1);

void BM_Collides(benchmark::State& state) {
    const CollisionSpheres& env = environment();
    const std::vector<Capsule> q = queries(state.range(0) != 0, 1 << 16);
    std::size_t i = 0, hits = 0;
    for (auto _ : state) hits += env.collides(q[i++ & (q.size() - 1)], 0.005) ? 1 : 0;
    state.SetItemsProcessed(state.iterations());
    state.counters["colliding_%"] = 100.0 * double(hits) / double(state.iterations());
    state.SetLabel(state.range(0) ? "capsule" : "sphere");
}
BENCHMARK(BM_Collides)->Arg(0)->Arg(1);

}  // namespace
}  // namespace surfgrow::bench

BENCHMARK_MAIN();
