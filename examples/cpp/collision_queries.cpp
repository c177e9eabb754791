// Grow, then ask the collision model (one sphere per surface) how far a robot link is from the
// scanned surfaces. Usage: collision_queries (a simulated room corner).
#include <cmath>
#include <cstdio>

#include "example_cloud.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/robot/collision_spheres.hpp"

int main() try {
    const surfgrow::PointCloud cloud = example::room_corner();
    surfgrow::GrowerConfig grow;
    grow.mu = 0.012;
    const surfgrow::GrowResult r = surfgrow::grow_surfaces(cloud, grow);
    const auto env = surfgrow::CollisionSpheres::from_surfaces(r.surfaces);

    // A tool 0.2 m above the floor's middle, and a link (capsule) reaching down through it.
    const surfgrow::Sphere tool{surfgrow::Vec3d(0.5, 0.5, 0.2), 0.05};
    const surfgrow::Capsule link{surfgrow::Vec3d(0.5, 0.5, 0.3), surfgrow::Vec3d(0.5, 0.5, -0.05),
                                 0.02};
    const surfgrow::Proximity near = env.nearest(tool);
    std::printf("%zu spheres; tool clearance %.4f m (sphere %lld); link collides: %s\n", env.size(),
                near.clearance, static_cast<long long>(near.nearest),
                env.collides(link) ? "yes" : "no");
    // The floor is 0.2 m below the tool's centre: clearance 0.2 - 0.05 - sphere radius (mu), give
    // or take the noise and the spheres' spacing.
    const bool ok = std::abs(near.clearance - (0.2 - 0.05 - grow.mu)) < 0.005 && env.collides(link);
    return ok ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "collision_queries: %s\n", e.what());
    return 2;
}
