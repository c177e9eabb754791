// Coverage planning: goals and the visiting order over many small planes, as a cluttered room
// gives (Bobkov's office: 4,455 bound planes, whose 2-opt once took 10 s of the grow command).
#include <benchmark/benchmark.h>

#include <span>
#include <vector>

#include "surfgrow/robot/coverage.hpp"

namespace surfgrow::bench {
namespace {

// n plates 5 cm wide on a grid 0.2 m apart (60 per row), listed in a scrambled order.
BoundPlanes plates(int n) {
    BoundPlanes p;
    p.config.mu = 0.012;
    const int per_row = 60;
    for (int k = 0; k < n; ++k) {
        const int cell = static_cast<int>((static_cast<long long>(k) * 1237) % n);
        BoundPlane b;
        b.centroid = Vec3d(0.2 * (cell % per_row), 0.2 * (cell / per_row), 0);
        b.normal = Vec3d::UnitZ();
        b.u_axis = Vec3d::UnitX();
        b.v_axis = Vec3d::UnitY();
        b.polygons = {{{{-0.025, -0.025}, {0.025, -0.025}, {0.025, 0.025}, {-0.025, 0.025}}, {}}};
        b.area = 0.05 * 0.05;
        p.stats.area += b.area;
        p.planes.push_back(b);
    }
    return p;
}

void BM_PlanCoverage(benchmark::State& state) {
    const BoundPlanes planes = plates(static_cast<int>(state.range(0)));
    CoverageConfig cfg;
    cfg.threads = 1;
    for (auto _ : state) {
        const CoveragePlan plan = plan_coverage(planes, std::span<const Surface>{}, cfg);
        benchmark::DoNotOptimize(plan.stats.transition_length);
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_PlanCoverage)->Arg(300)->Arg(3000)->Arg(6000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace surfgrow::bench

BENCHMARK_MAIN();
