#include "surfgrow/io/result_outputs.hpp"

#include <future>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "surfgrow/core/grown_points.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/io/collision_io.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/occupancy_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/planes/plane_mesh.hpp"
#include "surfgrow/robot/sensor_origins.hpp"

namespace surfgrow::io {

bool is_result_file(std::string_view file_name) {
    static constexpr std::string_view kNames[] = {"surfaces.ply",
                                                  "surfaces.json",
                                                  "labels.bin",
                                                  "labels.txt",
                                                  "surfaces.csv",
                                                  "planes.json",
                                                  "planes.ply",
                                                  "planes.obj",
                                                  "coverage.json",
                                                  "coverage.ply",
                                                  "coverage.csv",
                                                  "occupancy.ply",
                                                  "occupancy.json",
                                                  "environment.bt",
                                                  "collision_spheres.json",
                                                  "collision_spheres.ply",
                                                  "surfaces.png",
                                                  "corner.png",
                                                  "run.json",
                                                  "eval.json",
                                                  "collision.json"};
    for (const std::string_view n : kNames)
        if (n == file_name) return true;
    return false;
}

namespace {

// environment.bt in memory (a few hundred KB) and what went into it.
struct OctomapBytes {
    std::string bytes;
    OctomapSummary summary;
    double seconds = 0.0;
};

OctomapBytes octomap_bytes(const OccupancyGrid& grid, const CloudView& cloud,
                           const GrowerConfig& config, OctomapCarver* carver) {
    const Stopwatch watch;
    const std::vector<std::uint8_t> rays = grown_point_mask(cloud, config);
    const SensorOrigins origins = sensor_origins(cloud, config);
    std::ostringstream out;
    OctomapBytes b;
    b.summary = carver ? carver->write(out, grid, cloud, rays, origins, config.threads)
                       : write_octomap_bt(out, grid, cloud, rays, origins, config.threads);
    b.bytes = std::move(out).str();
    b.seconds = watch.seconds();
    return b;
}

// stage_occupancy, with environment.bt already on its way when `ready` is given.
OccupancySummary stage_occupancy_files(OutputTransaction& tx, const OccupancyGrid& grid,
                                       const CloudView& cloud, const GrowerConfig& config,
                                       const ResultMeta& meta, const OccupancyOutputs& which,
                                       std::future<OctomapBytes>* ready, OctomapCarver* carver) {
    OccupancySummary summary;
    summary.occupied_cubes = grid.size();
    summary.registered_points = grid.registered_points();
    // An output not written again would describe another grid: it goes.
    for (const auto& [written, name] : {std::pair{which.ply, "occupancy.ply"},
                                        {which.octomap, "environment.bt"},
                                        {which.json, "occupancy.json"}})
        if (!written) tx.drop(name);
    if (which.ply)
        tx.add("occupancy.ply", [&](std::ostream& o) { write_occupancy_ply(o, grid, meta); });
    if (which.octomap) {
        const OctomapBytes b = ready ? ready->get() : octomap_bytes(grid, cloud, config, carver);
        tx.add("environment.bt", [&](std::ostream& o) {
            o.write(b.bytes.data(), static_cast<std::streamsize>(b.bytes.size()));
        });
        summary.octomap = b.summary;
        summary.octomap_seconds = b.seconds;
        summary.octomap_written = true;
    }
    if (which.json)
        tx.add("occupancy.json", [&](std::ostream& o) {
            write_occupancy_json(o, grid, meta,
                                 summary.octomap_written ? &summary.octomap : nullptr);
        });
    return summary;
}

}  // namespace

OccupancySummary stage_result(OutputTransaction& tx, const CloudView& cloud,
                              const PipelineConfig& config, const PipelineResult& result,
                              const ResultMeta& meta, const ResultFiles& files,
                              const std::function<void()>& meanwhile, OctomapCarver* carver) {
    const GrowResult& r = result.grow;
    // environment.bt's rays take longest of the outputs and need none of the others: with more
    // than one thread they are cast while the caller's files (the pictures) and the others are
    // written.
    std::future<OctomapBytes> octomap;
    if (result.occupancy && files.octomap && resolve_threads(config.grow.threads) > 1)
        octomap = std::async(std::launch::async, [&] {
            return octomap_bytes(*result.occupancy, cloud, config.grow, carver);
        });
    if (meanwhile) meanwhile();
    tx.add("surfaces.ply", [&](std::ostream& o) { write_surfaces_ply(o, r.surfaces, meta); });
    tx.add("surfaces.json", [&](std::ostream& o) { write_result_json(o, r, config.grow, meta); });
    if (files.labels) tx.add(kLabelsFile, [&](std::ostream& o) { write_labels_bin(o, r.labels); });
    if (files.labels_txt)
        tx.add("labels.txt", [&](std::ostream& o) { write_labels_txt(o, r.labels); });
    if (files.csv)
        tx.add("surfaces.csv", [&](std::ostream& o) { write_surfaces_csv(o, r.surfaces, meta); });
    if (result.planes) stage_planes(tx, *result.planes, meta, files.planes_obj);
    if (result.coverage) stage_coverage(tx, *result.coverage, meta, files.coverage_csv);
    OccupancySummary occupancy;
    if (result.occupancy && (files.occupancy || files.octomap)) {
        OccupancyOutputs which;
        which.ply = which.json = files.occupancy;
        which.octomap = files.octomap;
        occupancy = stage_occupancy_files(tx, *result.occupancy, cloud, config.grow, meta, which,
                                          octomap.valid() ? &octomap : nullptr, carver);
    }
    if (result.collision) stage_collision(tx, *result.collision, meta);
    return occupancy;
}

void stage_planes(OutputTransaction& tx, const BoundPlanes& planes, const ResultMeta& meta,
                  bool obj) {
    const PlaneMesh mesh = mesh_bound_planes(planes);
    tx.add("planes.json", [&](std::ostream& o) { write_planes_json(o, planes, meta); });
    tx.add("planes.ply", [&](std::ostream& o) { write_planes_ply(o, mesh, meta); });
    if (obj)
        tx.add("planes.obj", [&](std::ostream& o) { write_planes_obj(o, mesh, meta); });
    else
        tx.drop("planes.obj");
    // Planned or evaluated from the old planes: stale unless staged again.
    for (const char* stale : {"coverage.json", "coverage.ply", "coverage.csv", "eval.json"})
        tx.drop(stale);
}

void stage_coverage(OutputTransaction& tx, const CoveragePlan& plan, const ResultMeta& meta,
                    bool csv) {
    tx.add("coverage.json", [&](std::ostream& o) { write_coverage_json(o, plan, meta); });
    tx.add(kCoverageGoalsFile, [&](std::ostream& o) { write_coverage_ply(o, plan, meta); });
    if (csv)
        tx.add("coverage.csv", [&](std::ostream& o) { write_coverage_csv(o, plan, meta); });
    else
        tx.drop("coverage.csv");
}

OccupancySummary stage_occupancy(OutputTransaction& tx, const OccupancyGrid& grid,
                                 const CloudView& cloud, const GrowerConfig& config,
                                 const ResultMeta& meta, const OccupancyOutputs& which) {
    return stage_occupancy_files(tx, grid, cloud, config, meta, which, nullptr, nullptr);
}

void stage_collision(OutputTransaction& tx, const CollisionSpheres& spheres,
                     const ResultMeta& meta) {
    tx.add("collision_spheres.json",
           [&](std::ostream& o) { write_collision_spheres_json(o, spheres, meta); });
    tx.add(kCollisionSpheresFile,
           [&](std::ostream& o) { write_collision_spheres_ply(o, spheres, meta); });
}

}  // namespace surfgrow::io
