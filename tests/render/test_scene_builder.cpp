// Building scenes from surfaces and clouds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surfgrow/core/error.hpp"
#include "surfgrow/render/group_colors.hpp"
#include "surfgrow/render/scene_builder.hpp"

using namespace surfgrow;
using namespace surfgrow::render;

namespace {

Surface surface(const Vec3d& home, const Vec3d& centroid, const Vec3d& normal, double radius) {
    Surface s;
    s.home = home;
    s.centroid = centroid;
    s.normal = normal;
    s.radius = radius;
    return s;
}

}  // namespace

TEST(SceneBuilder, DiskSitsOnThePlaneUnderTheHomePoint) {
    // Home point 3 mm above the plane z = 1 through the centroid.
    const std::vector<Surface> s{surface({0.2, 0.1, 1.003}, {0, 0, 1}, {0, 0, 2}, 0.012)};
    const Scene scene = scene_from_surfaces(s);
    ASSERT_EQ(scene.disks.size(), 1u);
    EXPECT_TRUE(scene.disks[0].center.isApprox(Vec3d(0.2, 0.1, 1.0), 1e-12));
    EXPECT_TRUE(scene.disks[0].normal.isApprox(Vec3d::UnitZ(), 1e-12));  // normalised
    EXPECT_DOUBLE_EQ(scene.disks[0].radius, 0.012);
    EXPECT_EQ(scene.disks[0].color, id_color(0));
    EXPECT_TRUE(scene.lines.empty());
    EXPECT_DOUBLE_EQ(scene.point_depth_bias, 0.012);
}

TEST(SceneBuilder, ColoursBySurfaceOrGroup) {
    std::vector<Surface> s;
    for (int i = 0; i < 4; ++i)
        s.push_back(surface({double(i), 0, 0}, {double(i), 0, 0}, {0, 0, 1}, 0.01));
    const Scene by_surface = scene_from_surfaces(s);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(by_surface.disks[std::size_t(i)].color, id_color(i));

    SurfaceStyle style;
    style.groups = {7, 7, -1, 3};
    // In group_colors' palette: the larger group first, the other the least used colour.
    const Scene by_group = scene_from_surfaces(s, style);
    EXPECT_EQ(by_group.disks[0].color, kGroupPalette[0]);
    EXPECT_EQ(by_group.disks[1].color, kGroupPalette[0]);
    EXPECT_EQ(by_group.disks[2].color, kUnassignedGrey);
    EXPECT_EQ(by_group.disks[3].color, kGroupPalette[1]);

    style.groups = {1, 2};
    try {
        (void)scene_from_surfaces(s, style);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
    }
}

TEST(SceneBuilder, NormalsStartAtTheDiskCentre) {
    const std::vector<Surface> s{surface({1, 2, 3}, {1, 2, 3}, {0, 1, 0}, 0.02)};
    SurfaceStyle style;
    style.normals = true;
    Scene scene = scene_from_surfaces(s, style);
    ASSERT_EQ(scene.lines.size(), 1u);
    EXPECT_TRUE(scene.lines[0].from.isApprox(Vec3d(1, 2, 3)));
    EXPECT_TRUE(scene.lines[0].to.isApprox(Vec3d(1, 2.02, 3)));  // default length: radius
    EXPECT_EQ(scene.lines[0].disk, 0);
    EXPECT_EQ(scene.lines[0].color, kNormalRed);
    style.normal_length = 0.5;
    scene = scene_from_surfaces(s, style);
    EXPECT_TRUE(scene.lines[0].to.isApprox(Vec3d(1, 2.5, 3)));
}

TEST(SceneBuilder, UnusableSurfacesKeepTheirPlaceAndDrawNothing) {
    const std::vector<Surface> s{surface({0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0.01),
                                 surface({1, 0, 0}, {1, 0, 0}, {0, 0, 1}, 0.01)};
    const Scene scene = scene_from_surfaces(s);
    ASSERT_EQ(scene.disks.size(), 2u);  // disks[i] is surfaces[i]
    EXPECT_EQ(scene.disks[0].radius, 0.0);
    EXPECT_EQ(scene.disks[1].radius, 0.01);
}

TEST(SceneBuilder, PointsTakeTheirSurfaceColourAndUnregisteredAreGrey) {
    std::vector<Surface> s{surface({0, 0, 0}, {0, 0, 0}, {0, 0, 1}, 0.01),
                           surface({1, 0, 0}, {1, 0, 0}, {0, 0, 1}, 0.01)};
    Scene scene = scene_from_surfaces(s);
    PointCloud cloud;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    cloud.points = {{0, 0, 0}, {1, 0, 0}, {5, 5, 5}, {nan, 0, 0}, {2, 0, 0}};
    const std::vector<std::int32_t> labels{0, 1, -1, 0, 9};
    SurfaceStyle style;
    add_points(scene, cloud, labels, s.size(), style);
    ASSERT_EQ(scene.points.size(), 4u);  // the NaN point is skipped
    EXPECT_EQ(scene.points[0].color, scaled(id_color(0), style.point_shade));
    EXPECT_EQ(scene.points[0].disk, 0);
    EXPECT_EQ(scene.points[1].color, scaled(id_color(1), style.point_shade));
    EXPECT_EQ(scene.points[1].disk, 1);
    EXPECT_EQ(scene.points[2].color, kUnassignedGrey);
    EXPECT_EQ(scene.points[2].disk, -1);
    EXPECT_EQ(scene.points[3].color, scaled(id_color(9), style.point_shade));  // not a surface
    EXPECT_EQ(scene.points[3].disk, -1);

    Scene plain;
    add_points(plain, cloud, {}, 0);
    for (const ScenePoint& p : plain.points) EXPECT_EQ(p.color, kUnassignedGrey);

    const std::vector<std::int32_t> short_labels{0};
    EXPECT_THROW(add_points(plain, cloud, short_labels, 2), Error);
}

TEST(SceneBuilder, LegendLine) {
    EXPECT_EQ(legend_line(276480, 5231, 0.99412),
              "276480 points -> 5231 surfaces, 99.4% registered");
    EXPECT_EQ(legend_line(0, 0, 0.0), "0 points -> 0 surfaces, 0.0% registered");
    EXPECT_EQ(legend_line(1000000, 20000, 1.0),
              "1000000 points -> 20000 surfaces, 100.0% registered");
}
