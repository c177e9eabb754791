#include "surfgrow/io/result_outputs.hpp"

#include "surfgrow/core/grown_points.hpp"
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
                                                  "labels.txt",
                                                  "surfaces.csv",
                                                  "planes.json",
                                                  "planes.ply",
                                                  "planes.obj",
                                                  "coverage.json",
                                                  "coverage.csv",
                                                  "occupancy.ply",
                                                  "occupancy.json",
                                                  "environment.bt",
                                                  "collision_spheres.json",
                                                  "surfaces.png",
                                                  "corner.png",
                                                  "run.json",
                                                  "eval.json",
                                                  "collision.json"};
    for (const std::string_view n : kNames)
        if (n == file_name) return true;
    return false;
}

OccupancySummary stage_result(OutputTransaction& tx, const CloudView& cloud,
                              const PipelineConfig& config, const PipelineResult& result,
                              const ResultMeta& meta, const ResultFiles& files) {
    const GrowResult& r = result.grow;
    tx.add("surfaces.ply", [&](std::ostream& o) { write_surfaces_ply(o, r.surfaces, meta); });
    tx.add("surfaces.json", [&](std::ostream& o) { write_result_json(o, r, config.grow, meta); });
    if (files.labels) tx.add("labels.txt", [&](std::ostream& o) { write_labels_txt(o, r.labels); });
    if (files.csv)
        tx.add("surfaces.csv", [&](std::ostream& o) { write_surfaces_csv(o, r.surfaces, meta); });
    if (result.planes) stage_planes(tx, *result.planes, meta, files.planes_obj);
    if (result.coverage) stage_coverage(tx, *result.coverage, meta);
    OccupancySummary occupancy;
    if (result.occupancy && (files.occupancy || files.octomap)) {
        OccupancyOutputs which;
        which.ply = which.json = files.occupancy;
        which.octomap = files.octomap;
        occupancy = stage_occupancy(tx, *result.occupancy, cloud, config.grow, meta, which);
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
    for (const char* stale : {"coverage.json", "coverage.csv", "eval.json"}) tx.drop(stale);
}

void stage_coverage(OutputTransaction& tx, const CoveragePlan& plan, const ResultMeta& meta) {
    tx.add("coverage.json", [&](std::ostream& o) { write_coverage_json(o, plan, meta); });
    tx.add("coverage.csv", [&](std::ostream& o) { write_coverage_csv(o, plan, meta); });
}

OccupancySummary stage_occupancy(OutputTransaction& tx, const OccupancyGrid& grid,
                                 const CloudView& cloud, const GrowerConfig& config,
                                 const ResultMeta& meta, const OccupancyOutputs& which) {
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
        const std::vector<std::uint8_t> rays = grown_point_mask(cloud, config);
        const SensorOrigins origins = sensor_origins(cloud, config);
        tx.add("environment.bt", [&](std::ostream& o) {
            summary.octomap = write_octomap_bt(o, grid, cloud, rays, origins, config.threads);
        });
        summary.octomap_written = true;
    }
    if (which.json)
        tx.add("occupancy.json", [&](std::ostream& o) {
            write_occupancy_json(o, grid, meta,
                                 summary.octomap_written ? &summary.octomap : nullptr);
        });
    return summary;
}

void stage_collision(OutputTransaction& tx, const CollisionSpheres& spheres,
                     const ResultMeta& meta) {
    tx.add("collision_spheres.json",
           [&](std::ostream& o) { write_collision_spheres_json(o, spheres, meta); });
}

}  // namespace surfgrow::io
