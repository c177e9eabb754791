#include "test_support.hpp"

#include <unistd.h>

#include <Eigen/Geometry>  // cross() in sample_rect()
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "surfgrow/core/cube_index.hpp"

namespace surfgrow::test {

namespace fs = std::filesystem;

fs::path source_dir() {
    if (const char* env = std::getenv("SURFGROW_SOURCE_DIR")) return fs::path(env);
    return fs::current_path();
}

std::optional<fs::path> real_data_dir() {
    const fs::path dir = source_dir().parent_path() / "shared" / "data" / "real";
    std::error_code ec;
    if (fs::is_directory(dir, ec)) return dir;
    return std::nullopt;
}

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "tmp";
    std::replace(name.begin(), name.end(), '/', '_');
    path_ = fs::temp_directory_path() / ("surfgrow-test-" + std::to_string(::getpid()) + "-" +
                                         std::to_string(counter++) + "-" + name);
    fs::remove_all(path_);
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

std::string read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void write_bytes(const fs::path& file, const std::string& bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void sample_rect(const Rect& rect, double spacing, double jitter, double sigma,
                 std::mt19937_64& rng, std::vector<Vec3f>& points, std::vector<int32_t>* labels,
                 int32_t label) {
    std::uniform_real_distribution<double> uni(-jitter * spacing, jitter * spacing);
    std::normal_distribution<double> gauss(0.0, sigma > 0 ? sigma : 1.0);
    const Vec3d n = rect.normal();
    const int nu = static_cast<int>(std::floor(2 * rect.half_u / spacing));
    const int nv = static_cast<int>(std::floor(2 * rect.half_v / spacing));
    for (int i = 0; i <= nu; ++i) {
        for (int j = 0; j <= nv; ++j) {
            const double a =
                std::clamp(-rect.half_u + i * spacing + uni(rng), -rect.half_u, rect.half_u);
            const double b =
                std::clamp(-rect.half_v + j * spacing + uni(rng), -rect.half_v, rect.half_v);
            const double h = sigma > 0 ? gauss(rng) : 0.0;
            const Vec3d p = rect.center + a * rect.u + b * rect.v + h * n;
            points.push_back(p.cast<float>());
            if (labels) labels->push_back(label);
        }
    }
}

void lattice_patches(double step, const Vec3d& base, std::uint64_t seed,
                     std::vector<Vec3f>& points) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> noise(-10, 10);
    auto tilt = [](double u, double v, double ku, double kv) {
        return std::round(ku * u + kv * v);
    };
    for (int patch = 0; patch < 3; ++patch) {
        for (int a = 0; a < 24; ++a) {
            for (int b = 0; b < 24; ++b) {
                const int r = noise(rng);
                const double n = r == -10 ? -1.0 : r == 10 ? 1.0 : 0.0;
                const double u = a, v = b;  // lattice coordinates: a floor and two walls
                Vec3d l(u, v, tilt(u, v, 0.3, 0.2) + n);
                if (patch == 1) l = Vec3d(u, 30 + tilt(u, v, 0.25, -0.1) + n, v + 10);
                if (patch == 2) l = Vec3d(30 + tilt(u, v, 0.2, 0.15) + n, u, v + 10);
                points.push_back((base + step * l).cast<float>());
            }
        }
    }
}

double mu_for_cube_side(double side) {
    const std::vector<Vec3f> probe = {Vec3f::Zero()};
    double mu = side / (1.0 + 1.0 / (1 << 20));
    for (int k = 0; k < 16; ++k) {
        const double got = CubeIndex(probe, mu).cube_size();
        if (got == side) return mu;
        mu = std::nextafter(mu, got < side ? side : 0.0);
    }
    ADD_FAILURE() << "no mu gives a cube side of exactly " << side;
    return mu;
}

std::vector<Rect> box_faces(const Vec3d& min, const Vec3d& max) {
    const Vec3d c = 0.5 * (min + max);
    const Vec3d h = 0.5 * (max - min);
    const Vec3d X = Vec3d::UnitX(), Y = Vec3d::UnitY(), Z = Vec3d::UnitZ();
    return {
        {c - h.x() * X, Y, Z, h.y(), h.z()}, {c + h.x() * X, Y, Z, h.y(), h.z()},
        {c - h.y() * Y, X, Z, h.x(), h.z()}, {c + h.y() * Y, X, Z, h.x(), h.z()},
        {c - h.z() * Z, X, Y, h.x(), h.y()}, {c + h.z() * Z, X, Y, h.x(), h.y()},
    };
}

std::vector<Rect> ibeam_faces(double length, double height, double flange_width,
                              double flange_thickness, double web_thickness) {
    const Vec3d X = Vec3d::UnitX(), Y = Vec3d::UnitY(), Z = Vec3d::UnitZ();
    const double hl = length / 2, hw = flange_width / 2, hh = height / 2;
    const double inner = hh - flange_thickness;  // z of the flanges' inner faces
    const double web_half = web_thickness / 2;
    const double ledge = (hw - web_half) / 2;  // half width of a flange face beside the web
    std::vector<Rect> f;
    f.push_back({{0, 0, hh}, X, Y, hl, hw});   // top of top flange
    f.push_back({{0, 0, -hh}, X, Y, hl, hw});  // bottom of bottom flange
    for (double side : {-1.0, 1.0}) {
        const double y_mid = side * (web_half + ledge);
        f.push_back({{0, y_mid, inner}, X, Y, hl, ledge});        // underside of top flange
        f.push_back({{0, y_mid, -inner}, X, Y, hl, ledge});       // top side of bottom flange
        f.push_back({{0, side * web_half, 0}, X, Z, hl, inner});  // web face
    }
    return f;
}

double median(std::vector<double> values) {
    return quantile(std::move(values), 0.5);
}

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return std::nan("");
    const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * (values.size() - 1) + 0.5);
    std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
    return values[k];
}

}  // namespace surfgrow::test
