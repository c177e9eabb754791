// Rendering speed at the sizes: 1600 x 1200 with 10 000 disks, and 1 M raw points.
// threads 0 = all cores; wall-clock time (UseRealTime), since the work runs on worker threads.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene.hpp"

using namespace surfgrow;
using namespace surfgrow::render;

namespace {

struct Face {
    Vec3d center, u, v;  // u, v: half-size axes
};

// An I-beam channel in metres: two beams (flanges and web faces), deck and floor.
std::vector<Face> channel_faces() {
    const Vec3d X = Vec3d::UnitX(), Y = Vec3d::UnitY(), Z = Vec3d::UnitZ();
    std::vector<Face> f;
    for (double y : {-0.45, 0.45}) {
        f.push_back({{0, y, 0}, 0.8 * X, 0.28 * Z});       // web
        f.push_back({{0, y, 0.28}, 0.8 * X, 0.125 * Y});   // top flange underside
        f.push_back({{0, y, -0.28}, 0.8 * X, 0.125 * Y});  // bottom flange top
        f.push_back({{0, y, -0.30}, 0.8 * X, 0.125 * Y});  // bottom flange underside
    }
    f.push_back({{0, 0, 0.30}, 0.8 * X, 0.7 * Y});   // deck
    f.push_back({{0, 0, -0.90}, 0.8 * X, 0.7 * Y});  // floor
    return f;
}

double area(const Face& f) {
    return 4 * f.u.norm() * f.v.norm();
}

// `n` disks of radius 12 mm spread over the faces by area, normals jittered by a few degrees,
// all facing the middle of the channel (as the grower orients them towards the scanner).
Scene channel_disks(std::size_t n, std::size_t points) {
    const auto faces = channel_faces();
    double total = 0;
    for (const Face& f : faces) total += area(f);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> uni(-1, 1);
    std::normal_distribution<double> tilt(0, 0.04);
    Scene scene;
    scene.point_depth_bias = 0.012;
    for (std::size_t k = 0; k < faces.size(); ++k) {
        const Face& f = faces[k];
        Vec3d normal = f.u.cross(f.v).normalized();
        if (normal.dot(Vec3d(0, 0, -0.2) - f.center) < 0) normal = -normal;
        const auto count = static_cast<std::size_t>(double(n) * area(f) / total);
        for (std::size_t i = 0; i < count; ++i) {
            const Vec3d c = f.center + uni(rng) * f.u + uni(rng) * f.v;
            const Vec3d nn = (normal + Vec3d(tilt(rng), tilt(rng), tilt(rng))).normalized();
            scene.disks.push_back({c, nn, 0.012, id_color(static_cast<std::int64_t>(i))});
        }
        const auto pcount = static_cast<std::size_t>(double(points) * area(f) / total);
        for (std::size_t i = 0; i < pcount; ++i) {
            const Vec3d p = f.center + uni(rng) * f.u + uni(rng) * f.v + 0.002 * tilt(rng) * normal;
            scene.points.push_back({p.cast<float>(), id_color(static_cast<std::int64_t>(k))});
        }
    }
    scene.legend = "1000000 points -> 10000 surfaces, 99.4% registered";
    return scene;
}

void BM_RenderDisks(benchmark::State& state) {
    const Scene scene = channel_disks(static_cast<std::size_t>(state.range(0)), 0);
    RenderOptions options;  // 1600 x 1200, iso
    options.supersample = static_cast<int>(state.range(1));
    options.threads = static_cast<int>(state.range(2));
    for (auto _ : state) benchmark::DoNotOptimize(render_scene(scene, options));
    state.counters["disks"] = double(scene.disks.size());
}
BENCHMARK(BM_RenderDisks)
    ->ArgNames({"disks", "ss", "threads"})
    ->Args({10000, 3, 0})
    ->Args({10000, 3, 1})
    ->Args({10000, 2, 0})
    ->Args({10000, 1, 0})
    ->Args({40000, 3, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_RenderPoints(benchmark::State& state) {
    const Scene scene = channel_disks(10000, static_cast<std::size_t>(state.range(0)));
    RenderOptions options;
    options.threads = static_cast<int>(state.range(1));
    for (auto _ : state) benchmark::DoNotOptimize(render_scene(scene, options));
    state.counters["points"] = double(scene.points.size());
}
BENCHMARK(BM_RenderPoints)
    ->ArgNames({"points", "threads"})
    ->Args({1000000, 0})
    ->Args({1000000, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_RenderEmpty(benchmark::State& state) {
    Scene scene;
    scene.legend = "0 points -> 0 surfaces, 0.0% registered";
    for (auto _ : state) benchmark::DoNotOptimize(render_scene(scene, RenderOptions{}));
}
BENCHMARK(BM_RenderEmpty)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_EncodePng(benchmark::State& state) {
    const Image image = render_scene(channel_disks(10000, 0), RenderOptions{});
    std::size_t bytes = 0;
    const auto threads = static_cast<int>(state.range(0));
    for (auto _ : state) bytes = encode_png(image, threads).size();
    state.counters["bytes"] = double(bytes);
}
BENCHMARK(BM_EncodePng)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
