// Reading speed of the point-cloud formats: 1 M points from the page cache, per format/encoding.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>
#include <system_error>

#include "surfgrow/io/cloud_io.hpp"

namespace {

namespace fs = std::filesystem;
using surfgrow::PointCloud;
using surfgrow::Vec3d;
namespace io = surfgrow::io;

constexpr std::size_t kPoints = 1'000'000;

// Test files written once into a temporary folder, removed at exit.
class Files {
  public:
    Files()
        : dir_(fs::temp_directory_path() / ("surfgrow-bench-io-" + std::to_string(::getpid()))) {
        fs::create_directories(dir_);
        std::mt19937_64 rng(1);
        std::uniform_real_distribution<float> uni(-20.0f, 20.0f);
        PointCloud cloud;
        for (std::size_t i = 0; i < kPoints; ++i) {
            cloud.points.emplace_back(uni(rng), uni(rng), uni(rng));
        }
        PointCloud geo = cloud;
        geo.offset = Vec3d(512345, 5412345, 312);

        io::WriteOptions o;
        o.ply_encoding = io::PlyEncoding::kBinaryLittleEndian;
        io::write_cloud(dir_ / "binary_le.ply", cloud, o);
        io::write_cloud(dir_ / "binary_le_double.ply", geo, o);
        o.ply_encoding = io::PlyEncoding::kBinaryBigEndian;
        io::write_cloud(dir_ / "binary_be.ply", cloud, o);
        o.ply_encoding = io::PlyEncoding::kAscii;
        io::write_cloud(dir_ / "ascii.ply", cloud, o);
        o.pcd_encoding = io::PcdEncoding::kBinary;
        io::write_cloud(dir_ / "binary.pcd", cloud, o);
        o.pcd_encoding = io::PcdEncoding::kBinaryCompressed;
        io::write_cloud(dir_ / "binary_compressed.pcd", cloud, o);
        o.pcd_encoding = io::PcdEncoding::kAscii;
        io::write_cloud(dir_ / "ascii.pcd", cloud, o);
        io::write_cloud(dir_ / "cloud.xyz", cloud);
        io::write_cloud(dir_ / "geo.xyz", geo);
    }
    ~Files() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    Files(const Files&) = delete;
    Files& operator=(const Files&) = delete;
    [[nodiscard]] fs::path operator/(const char* name) const { return dir_ / name; }

  private:
    fs::path dir_;
};

const Files& files() {
    static const Files f;
    return f;
}

void BM_ReadCloud(benchmark::State& state, const char* name) {
    const fs::path path = files() / name;
    const auto bytes = static_cast<int64_t>(fs::file_size(path));
    (void)io::read_cloud(path);  // warm the page cache
    for (auto _ : state) {
        PointCloud cloud = io::read_cloud(path);
        benchmark::DoNotOptimize(cloud.points.data());
    }
    state.SetBytesProcessed(state.iterations() * bytes);
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(kPoints));
}

void BM_WriteCloud(benchmark::State& state, const char* name) {
    const fs::path path = files() / name;
    const PointCloud cloud = io::read_cloud(path);
    const fs::path out = files() / (std::string("out_") + name).c_str();
    io::WriteOptions o;
    o.pcd_encoding = io::PcdEncoding::kBinaryCompressed;
    for (auto _ : state) io::write_cloud(out, cloud, o);
    state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(fs::file_size(out)));
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(kPoints));
}

}  // namespace

BENCHMARK_CAPTURE(BM_ReadCloud, ply_binary_le_float, "binary_le.ply")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, ply_binary_be_float, "binary_be.ply")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, ply_binary_le_double_offset, "binary_le_double.ply")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, pcd_binary, "binary.pcd")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, pcd_binary_compressed, "binary_compressed.pcd")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, ply_ascii, "ascii.ply")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, pcd_ascii, "ascii.pcd")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, xyz_text, "cloud.xyz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadCloud, xyz_text_offset, "geo.xyz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WriteCloud, ply_binary_le_float, "binary_le.ply")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WriteCloud, pcd_binary_compressed, "binary_compressed.pcd")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WriteCloud, xyz_text, "cloud.xyz")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
