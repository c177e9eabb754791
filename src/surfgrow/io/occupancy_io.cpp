#include "surfgrow/io/occupancy_io.hpp"

#include <nlohmann/json.hpp>

#include "surfgrow/core/text.hpp"
#include "surfgrow/io/output_buffer.hpp"

namespace surfgrow::io {

namespace {

nlohmann::ordered_json vec_json(const Vec3d& v) {
    return nlohmann::ordered_json::array({v.x(), v.y(), v.z()});
}

}  // namespace

void write_occupancy_ply(std::ostream& out, const OccupancyGrid& grid, const ResultMeta& meta) {
    const bool wide = meta.offset != Vec3d::Zero();  // keep georeferenced precision
    const std::string_view pos = wide ? "double" : "float";
    const Vec3d origin = grid.origin() + meta.offset;
    OutputBuffer buf(out);
    buf.append(cat({"ply\nformat binary_little_endian 1.0\n",
                    "comment surfgrow occupancy: one vertex per occupied cube, at its centre\n",
                    "comment units ",
                    meta.units,
                    "\ncomment result_id ",
                    meta.result_id,
                    "\ncomment mu ",
                    num(grid.mu()),
                    "\ncomment cube_size ",
                    num(grid.cube_size()),
                    "\ncomment origin ",
                    num(origin.x()),
                    " ",
                    num(origin.y()),
                    " ",
                    num(origin.z()),
                    "\nelement vertex ",
                    std::to_string(grid.size()),
                    "\nproperty ",
                    pos,
                    " x\nproperty ",
                    pos,
                    " y\nproperty ",
                    pos,
                    " z\n",
                    "property uint count\nend_header\n"}));
    for (std::size_t k = 0; k < grid.size(); ++k) {
        const Vec3d c = grid.centre(grid.cells()[k]) + meta.offset;
        for (int a = 0; a < 3; ++a) {
            if (wide)
                buf.put_binary(c[a], false);
            else
                buf.put_binary(static_cast<float>(c[a]), false);
        }
        buf.put_binary(grid.point_counts()[k], false);
    }
    buf.flush();
}

void write_occupancy_json(std::ostream& out, const OccupancyGrid& grid, const ResultMeta& meta,
                          const OctomapSummary* octomap) {
    const Aabb b = grid.bounds();
    nlohmann::ordered_json j = {
        {"format", "surfgrow-occupancy"},
        {"version", 1},
        {"units", meta.units},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"mu", grid.mu()},
        {"cube_size", grid.cube_size()},
        {"origin", vec_json(grid.origin() + meta.offset)},
        {"cells",
         "cube (i, j, k) covers origin + [i, i+1) x [j, j+1) x [k, k+1) times cube_size; "
         "occupancy.ply lists the centres, origin + (i + 0.5, j + 0.5, k + 0.5) * cube_size"},
        {"occupied_cubes", grid.size()},
        {"registered_points", grid.registered_points()},
        {"bounds", b.empty() ? nlohmann::ordered_json(nullptr)
                             : nlohmann::ordered_json{{"min", vec_json(b.min + meta.offset)},
                                                      {"max", vec_json(b.max + meta.offset)}}},
    };
    if (octomap) {
        j["octomap"] = {
            {"file", "environment.bt"},
            {"resolution", octomap->resolution},
            {"frame_offset", vec_json(meta.offset)},
            {"frame",
             "OctoMap coordinates are file coordinates minus frame_offset; leaf k covers "
             "[k, k+1) times resolution on each axis; each occupied cube is the leaf holding "
             "its centre"},
            {"occupied_leaves", octomap->occupied},
            {"free_leaves", octomap->free},
            {"rays", octomap->rays},
            {"carving", sensor_origins_name(octomap->carving)},
        };
    }
    out << j.dump(1) << "\n";
}

}  // namespace surfgrow::io
