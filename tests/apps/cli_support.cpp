#include "cli_support.hpp"

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>

#include "support/test_support.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::test {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const Vec3d kBoxMin(-0.2, -0.15, 0.4), kBoxMax(0.2, 0.15, 0.7);

json xyz(const Vec3d& p) {
    return json::array({p.x(), p.y(), p.z()});
}

}  // namespace

CliRun run_surfgrow(const std::string& args) {
    const std::string cmd = cat({SURFGROW_CLI, " ", args, " 2>&1"});
    CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.out += buf.data();
    const int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::string quoted(const fs::path& p) {
    return cat({"'", p.string(), "'"});
}

GrownBox grow_box(const fs::path& dir) {
    GrownBox box;
    std::mt19937_64 rng(3);
    for (const auto& f : box_faces(kBoxMin, kBoxMax))
        sample_rect(f, 0.005, 0.3, 0.001, rng, box.points.points);
    for (std::size_t i = 5; i < box.points.size(); i += 997)
        box.points.points[i] = Vec3f::Constant(std::nanf(""));
    box.cloud = dir / "box.ply";
    box.out = dir / "out";
    io::write_cloud(box.cloud, box.points);
    const CliRun r =
        run_surfgrow(cat({"grow ", quoted(box.cloud), " -o ", quoted(box.out), " --seed 1 -q"}));
    if (r.code != 0) throw std::runtime_error("surfgrow grow failed: " + r.out);
    box.result = io::read_result_json(box.out / "surfaces.json");
    return box;
}

std::size_t write_layer_fixtures(const GrownBox& box) {
    json planes = json::array();
    int id = 0;
    for (const Rect& f : box_faces(kBoxMin, kBoxMax)) {
        const Vec3d n = f.normal();
        json boundary = json::array();
        for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
            boundary.push_back(xyz(f.center + a * f.half_u * f.u + b * f.half_v * f.v));
        json surfaces = json::array();
        for (std::size_t i = 0; i < box.result.surfaces.size(); ++i) {
            const Surface& s = box.result.surfaces[i];
            if (std::abs(s.normal.dot(n)) > 0.9 && std::abs(n.dot(s.home - f.center)) < 0.01)
                surfaces.push_back(i);
        }
        planes.push_back(
            {{"id", id++}, {"normal", xyz(n)}, {"boundary", boundary}, {"surfaces", surfaces}});
    }
    const json planes_file = {
        {"format", "surfgrow-planes"}, {"version", 1}, {"units", "m"}, {"planes", planes}};
    write_bytes(box.out / "planes.json", planes_file.dump(1));

    json goals = json::array();
    for (int row = 0; row < 4; ++row)
        for (int k = 0; k < 6; ++k) {
            const int col = row % 2 ? 5 - k : k;  // a zigzag, as a blasting nozzle would go
            goals.push_back({{"position", xyz({-0.15, -0.1 + 0.04 * col, 0.46 + 0.06 * row})}});
        }
    const json coverage = {
        {"format", "surfgrow-coverage"}, {"version", 1}, {"units", "m"}, {"goals", goals}};
    write_bytes(box.out / "coverage.json", coverage.dump(1));
    return goals.size();
}

}  // namespace surfgrow::test
