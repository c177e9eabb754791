// Kernels of surface growing: cube index build, growing, whole pipeline; points/s and memory.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "simulated_scans.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/surface_grower.hpp"

namespace surfgrow::bench {
namespace {

// One full paper scan of the I-beam channel (360 x 768 rays) or a 4-pose fusion (~1 M points).
const PointCloud& cloud_for(int poses) {
    static const PointCloud one = ibeam_channel_scan(1);
    static const PointCloud four = ibeam_channel_scan(4);
    return poses == 1 ? one : four;
}

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;
}

void BM_CubeIndexBuild(benchmark::State& state) {
    const PointCloud& cloud = cloud_for(static_cast<int>(state.range(0)));
    const int threads = static_cast<int>(state.range(1));
    for (auto _ : state) {
        CubeIndex index(cloud.points, 0.012, {}, threads);
        benchmark::DoNotOptimize(index.cube_count());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(cloud.size()));
    state.counters["points"] = static_cast<double>(cloud.size());
}
BENCHMARK(BM_CubeIndexBuild)->ArgsProduct({{1, 4}, {1, 2}})->Unit(benchmark::kMillisecond);

void BM_Grow(benchmark::State& state) {
    const PointCloud& cloud = cloud_for(static_cast<int>(state.range(0)));
    GrowerConfig cfg;
    cfg.threads = static_cast<int>(state.range(1));
    GrowResult r;
    for (auto _ : state) {
        r = grow_surfaces(cloud, cfg);
        benchmark::DoNotOptimize(r.surfaces.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(cloud.size()));
    state.counters["points"] = static_cast<double>(cloud.size());
    state.counters["surfaces"] = static_cast<double>(r.stats.surfaces);
    state.counters["registered_%"] = 100 * r.stats.registered_fraction();
    state.counters["grown_%"] = 100 * r.stats.registered_grown_fraction();
    state.counters["index_ms"] = 1000 * r.stats.seconds.index;
    state.counters["grow_ms"] = 1000 * r.stats.seconds.grow;
    state.counters["attach_ms"] = 1000 * r.stats.seconds.attach;
    state.counters["finish_ms"] = 1000 * r.stats.seconds.finish;
    state.counters["peak_rss_MB"] = peak_rss_mb();
}
BENCHMARK(BM_Grow)->ArgsProduct({{1, 4}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace surfgrow::bench

BENCHMARK_MAIN();
