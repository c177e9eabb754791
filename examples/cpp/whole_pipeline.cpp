// The whole job of `surfgrow grow` in one call: surfaces, bound planes, coverage goals, the
// occupancy grid and collision spheres, from one configuration.
// Usage: whole_pipeline [cloud] (metres; without a file, a simulated room corner).
#include <cstdio>

#include "example_cloud.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/pipeline/pipeline.hpp"

int main(int argc, char** argv) try {
    const surfgrow::PointCloud cloud =
        argc > 1 ? surfgrow::io::read_cloud(argv[1]) : example::room_corner();
    surfgrow::PipelineConfig job;  // every stage on, the paper's defaults
    job.grow.mu = 0.012;           // the library works in the cloud's units
    job.coverage->blast_radius = 0.05;
    job.coverage->standoff = 0.3;
    const surfgrow::PipelineResult out = surfgrow::run_pipeline(cloud, job);

    std::printf("%zu surfaces, %.1f%% registered\n", out.grow.surfaces.size(),
                100.0 * out.grow.stats.registered_fraction());
    std::printf("%zu bound planes, %zu coverage goals, %zu occupied cubes, %zu collision spheres\n",
                out.planes->planes.size(), out.coverage->goals.size(), out.occupancy->size(),
                out.collision->size());
    // A robot's question: how far is a 10 mm nozzle tip, 5 cm above the floor, from the steel?
    const surfgrow::Proximity tip =
        out.collision->nearest(surfgrow::Sphere{surfgrow::Vec3d(0.5, 0.5, 0.05), 0.01});
    std::printf("nozzle tip clearance %.3f m to surface %lld\n", tip.clearance,
                static_cast<long long>(tip.nearest));
    if (argc > 1) return 0;
    // The room corner: nearly every point registered, three large planes, goals on them, and
    // the floor 5 cm below the tip, less the tip's and a floor sphere's radius (mu).
    const bool ok = out.grow.stats.registered_fraction() > 0.95 && out.planes->planes.size() >= 3 &&
                    !out.coverage->goals.empty() && !out.occupancy->empty() && tip.nearest >= 0 &&
                    tip.clearance > 0.02 && tip.clearance < 0.05 - 0.01;
    return ok ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "whole_pipeline: %s\n", e.what());
    return 2;
}
