#include "cli_support.hpp"

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <stdexcept>

#include "support/test_support.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/coverage.hpp"

namespace surfgrow::test {

namespace fs = std::filesystem;

namespace {

const Vec3d kBoxMin(-0.2, -0.15, 0.4), kBoxMax(0.2, 0.15, 0.7);

}  // namespace

CliRun run_surfgrow(const std::string& args, const std::string& env) {
    const std::string cmd = cat({env, SURFGROW_CLI, " ", args, " 2>&1"});
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

GrownBox grow_box(const fs::path& dir, const std::string& grow_args) {
    GrownBox box;
    std::mt19937_64 rng(3);
    for (const auto& f : box_faces(kBoxMin, kBoxMax))
        sample_rect(f, 0.005, 0.3, 0.001, rng, box.points.points);
    for (std::size_t i = 5; i < box.points.size(); i += 997)
        box.points.points[i] = Vec3f::Constant(std::nanf(""));
    box.cloud = dir / "box.ply";
    box.out = dir / "out";
    io::write_cloud(box.cloud, box.points);
    const CliRun r = run_surfgrow(
        cat({"grow ", quoted(box.cloud), " -o ", quoted(box.out),
             " --seed 1 -q --no-planes --no-occupancy --no-octomap --no-collision", grow_args}));
    if (r.code != 0) throw std::runtime_error("surfgrow grow failed: " + r.out);
    box.result = io::read_result_json(box.out / "surfaces.json");
    return box;
}

std::size_t write_layer_fixtures(const GrownBox& box) {
    // The box's six faces as bound planes, in the format `surfgrow planes` writes.
    BoundPlanes planes;
    planes.plane_of_patch.assign(box.result.surfaces.size(), -1);
    planes.config.mu = box.result.config.mu;
    planes.stats.patches = box.result.surfaces.size();
    for (const Rect& f : box_faces(kBoxMin, kBoxMax)) {
        const auto id = static_cast<std::int32_t>(planes.planes.size());
        BoundPlane p;
        p.normal = f.normal();
        p.centroid = f.center;
        p.u_axis = f.u;
        p.v_axis = p.normal.cross(p.u_axis);
        PolygonWithHoles poly;
        for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
            poly.outer.emplace_back(a * f.half_u, b * f.half_v);
        for (const Vec2d& q : poly.outer) p.bounds.add(p.to_world(q));
        p.polygons.push_back(poly);
        p.area = 4 * f.half_u * f.half_v;
        for (std::size_t i = 0; i < box.result.surfaces.size(); ++i) {
            const Surface& s = box.result.surfaces[i];
            if (planes.plane_of_patch[i] < 0 && std::abs(s.normal.dot(p.normal)) > 0.9 &&
                std::abs(p.normal.dot(s.home - f.center)) < 0.01) {
                planes.plane_of_patch[i] = id;
                p.patches.push_back(static_cast<std::uint32_t>(i));
                p.point_count += s.point_count;
            }
        }
        planes.stats.area += p.area;
        planes.stats.points += p.point_count;
        planes.stats.patches_merged += p.patches.size();
        planes.planes.push_back(std::move(p));
    }
    std::ostringstream planes_file;
    io::write_planes_json(planes_file, planes, box.result.meta);
    write_bytes(box.out / "planes.json", planes_file.str());

    // A zigzag over one face, as a blasting nozzle would go, in the format `surfgrow coverage`
    // writes.
    CoveragePlan plan;
    plan.config.blast_radius = box.result.config.mu;
    for (int row = 0; row < 4; ++row)
        for (int k = 0; k < 6; ++k) {
            const int col = row % 2 ? 5 - k : k;
            CoverageGoal g;
            g.row = static_cast<std::uint32_t>(row);
            g.position = Vec3d(-0.15, -0.1 + 0.04 * col, 0.46 + 0.06 * row);
            g.tool_position = g.position - 0.3 * g.tool_axis;
            plan.goals.push_back(g);
        }
    plan.per_plane.push_back({0, static_cast<std::uint32_t>(plan.goals.size()), 0, 0.0, 0.0});
    plan.stats.goals = plan.goals.size();
    plan.stats.planes = 1;
    std::ostringstream coverage_file;
    io::write_coverage_json(coverage_file, plan, box.result.meta);
    write_bytes(box.out / "coverage.json", coverage_file.str());
    std::ostringstream goals_file;
    io::write_coverage_ply(goals_file, plan, box.result.meta);
    write_bytes(box.out / io::kCoverageGoalsFile, goals_file.str());
    return plan.goals.size();
}

}  // namespace surfgrow::test
