#include "surfgrow/io/robot_outputs.hpp"

#include "surfgrow/core/collision_spheres.hpp"
#include "surfgrow/core/sensor_origins.hpp"
#include "surfgrow/io/collision_io.hpp"
#include "surfgrow/io/occupancy_io.hpp"

namespace surfgrow::io {

OccupancySummary add_occupancy_outputs(OutputTransaction& tx, const PointCloud& cloud,
                                       std::span<const std::int32_t> labels,
                                       const GrowerConfig& config, const ResultMeta& meta,
                                       const OccupancyOutputs& which) {
    const OccupancyGrid grid = occupancy_grid(cloud, labels, config);
    OccupancySummary summary;
    summary.occupied_cubes = grid.size();
    summary.registered_points = grid.registered_points();
    if (which.ply)
        tx.add("occupancy.ply", [&](std::ostream& o) { write_occupancy_ply(o, grid, meta); });
    if (which.octomap) {
        const std::vector<std::uint8_t> rays = grown_point_mask(cloud, config);
        const SensorOrigins origins = sensor_origins(cloud, config);
        tx.add("environment.bt", [&](std::ostream& o) {
            summary.octomap = write_octomap_bt(o, grid, cloud, rays, origins);
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

void add_collision_outputs(OutputTransaction& tx, const GrowResult& result,
                           const ResultMeta& meta) {
    const CollisionSpheres spheres = CollisionSpheres::from_surfaces(result.surfaces);
    tx.add("collision_spheres.json",
           [&](std::ostream& o) { write_collision_spheres_json(o, spheres, meta); });
}

}  // namespace surfgrow::io
