// Grow, then bound planes (whole faces) and a coverage plan with approach poses over them.
// Usage: planes_and_coverage [cloud] (metres; without a file, a simulated room corner).
#include <cmath>
#include <cstdio>
#include <numbers>

#include "example_cloud.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/coverage.hpp"

int main(int argc, char** argv) try {
    const surfgrow::PointCloud cloud =
        argc > 1 ? surfgrow::io::read_cloud(argv[1]) : example::room_corner();
    surfgrow::GrowerConfig grow;
    grow.mu = 0.012;
    const surfgrow::GrowResult r = surfgrow::grow_surfaces(cloud, grow);

    surfgrow::BoundPlaneConfig pc;
    pc.mu = grow.mu;  // the same neighbourhood scale as the growing
    const surfgrow::BoundPlanes planes = surfgrow::compute_bound_planes(cloud, r, pc);

    surfgrow::CoverageConfig cc;
    cc.blast_radius = 0.05;  // each goal blasts a 50 mm disc
    cc.standoff = 0.3;       // from 0.3 m away
    const surfgrow::CoveragePlan plan = surfgrow::plan_coverage(planes, r, cc);

    for (const surfgrow::BoundPlane& p : planes.planes)
        std::printf("plane: normal (%+.3f %+.3f %+.3f), %.3f m^2, %llu points\n", p.normal.x(),
                    p.normal.y(), p.normal.z(), p.area,
                    static_cast<unsigned long long>(p.point_count));
    std::printf("%zu coverage goals\n", plan.goals.size());
    if (argc > 1) return 0;
    // The room corner has three faces, one along each axis, each about 1 m^2.
    int faces = 0;
    for (const surfgrow::BoundPlane& p : planes.planes)
        faces += p.area > 0.8 &&
                 p.normal.cwiseAbs().maxCoeff() > std::cos(2.0 * std::numbers::pi / 180.0);
    return faces == 3 && !plan.goals.empty() ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "planes_and_coverage: %s\n", e.what());
    return 2;
}
