// Grow a cloud: the README's first library example. Usage: grow_cloud [cloud.ply|.pcd|.xyz]
// (metres; without a file, a simulated room corner).
#include <cstdio>

#include "example_cloud.hpp"
#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/io/cloud_io.hpp"

int main(int argc, char** argv) try {
    const surfgrow::PointCloud cloud =
        argc > 1 ? surfgrow::io::read_cloud(argv[1]) : example::room_corner();
    surfgrow::GrowerConfig config;  // the paper's defaults: mu = 12 mm, min_pts = 10
    config.mu = 0.012;              // the library works in the cloud's units
    const surfgrow::GrowResult r = surfgrow::grow_surfaces(cloud, config);
    for (const surfgrow::Surface& s : r.surfaces) {
        (void)s;  // s.home, s.normal, s.plane(), s.point_count
    }
    std::printf("%zu points -> %zu surfaces, %.1f%% registered\n", cloud.size(), r.surfaces.size(),
                100.0 * r.stats.registered_fraction());

    // The same points read where they lie (a driver's buffer of x,y,z floats): no copy.
    const float* xyz = cloud.empty() ? nullptr : cloud.points.front().data();
    const std::size_t n = cloud.size();
    surfgrow::CloudView view({reinterpret_cast<const surfgrow::Vec3f*>(xyz), n});
    view.viewpoint = cloud.viewpoint;  // where the sensor stood
    const surfgrow::GrowResult mine = surfgrow::grow_surfaces(view, config);
    if (mine.labels != r.labels) {
        std::fprintf(stderr, "grow_cloud: the view grew other surfaces than the cloud\n");
        return 1;
    }
    return r.stats.registered_fraction() > 0.9 ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "grow_cloud: %s\n", e.what());
    return 2;
}
