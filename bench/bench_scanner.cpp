// Speed of the scan simulator and the fusion (issue 3: a full scan in well under a few seconds).
#include <benchmark/benchmark.h>

#include <vector>

#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace {

using namespace surfgrow::scanner;

// A full paper scan of a built-in scene: 360 tilts x 768 steps x n = 5 readings.
void simulate_full_scan(benchmark::State& state, const char* scene_name, int beam_samples) {
    const Scene scene(builtin_scene(scene_name));
    NoiseModel noise;
    noise.beam_samples = beam_samples;
    const ScanSimulator sim(scene, ScannerSpec{}, noise);
    const Pose pose = scene.description().scanner.home;
    std::uint64_t seed = 1;
    for (auto _ : state) {
        SimulatedScan scan = sim.simulate(pose, seed++);
        benchmark::DoNotOptimize(scan.raw.readings_mm.data());
    }
    state.counters["rays/s"] = benchmark::Counter(
        static_cast<double>(ScannerSpec{}.rays()) * static_cast<double>(state.iterations()),
        benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(simulate_full_scan, ibeam_channel, "ibeam-channel", 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(simulate_full_scan, ibeam_channel_no_mixed_pixels, "ibeam-channel", 1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(simulate_full_scan, room_corner, "room-corner", 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(simulate_full_scan, pipes, "pipes", 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Filtering (eq. 1), conversion and fusion of three full scans.
void fuse_three_scans(benchmark::State& state) {
    const SceneDescription desc = builtin_scene("ibeam-channel");
    const Scene scene(desc);
    const ScanSimulator sim(scene);
    std::vector<RawScan> raws;
    for (SimulatedScan& s : sim.simulate(scan_poses(desc.scanner, 3), 1))
        raws.push_back(std::move(s.raw));
    for (auto _ : state) {
        auto cloud = fuse_scans(raws);
        benchmark::DoNotOptimize(cloud.points.data());
    }
}
BENCHMARK(fuse_three_scans)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
