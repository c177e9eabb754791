// View presets, projection and framing.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "surfgrow/core/error.hpp"
#include "surfgrow/render/camera.hpp"

using namespace surfgrow;
using namespace surfgrow::render;

TEST(Camera, ParsesViewNames) {
    for (View v : {View::kFront, View::kSide, View::kTop, View::kIso})
        EXPECT_EQ(parse_view(view_name(v)), v);
    try {
        (void)parse_view("bottom");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
        EXPECT_NE(std::string(e.what()).find("bottom"), std::string::npos);
    }
}

TEST(Camera, PresetsAreOrthonormalAndRightHanded) {
    for (View v : {View::kFront, View::kSide, View::kTop, View::kIso}) {
        const Camera c = Camera::preset(v);
        EXPECT_NEAR(c.right().norm(), 1, 1e-12);
        EXPECT_NEAR(c.up().norm(), 1, 1e-12);
        EXPECT_NEAR(c.right().dot(c.up()), 0, 1e-12);
        EXPECT_NEAR(c.right().dot(c.forward()), 0, 1e-12);
        // right x up points at the viewer.
        EXPECT_TRUE(c.right().cross(c.up()).isApprox(-c.forward(), 1e-12));
    }
}

namespace {

// Screen offset of a world direction: (dx > 0: right, dy < 0: up, dz > 0: farther).
Vec3d moved(View v, const Vec3d& d) {
    const Camera c = Camera::preset(v);
    return c.project(d) - c.project(Vec3d::Zero());
}

}  // namespace

TEST(Camera, FrontLooksAlongPlusY) {
    EXPECT_GT(moved(View::kFront, Vec3d::UnitX()).x(), 0);  // x to the right
    EXPECT_LT(moved(View::kFront, Vec3d::UnitZ()).y(), 0);  // z up
    EXPECT_GT(moved(View::kFront, Vec3d::UnitY()).z(), 0);  // y away from the viewer
}

TEST(Camera, SideLooksAlongMinusX) {
    EXPECT_GT(moved(View::kSide, Vec3d::UnitY()).x(), 0);
    EXPECT_LT(moved(View::kSide, Vec3d::UnitZ()).y(), 0);
    EXPECT_LT(moved(View::kSide, Vec3d::UnitX()).z(), 0);  // +x is nearer
}

TEST(Camera, TopLooksDown) {
    EXPECT_GT(moved(View::kTop, Vec3d::UnitX()).x(), 0);
    EXPECT_LT(moved(View::kTop, Vec3d::UnitY()).y(), 0);  // y up on screen
    EXPECT_LT(moved(View::kTop, Vec3d::UnitZ()).z(), 0);  // +z is nearer
}

TEST(Camera, IsoKeepsZUpAndShowsThreeAxes) {
    const Vec3d x = moved(View::kIso, Vec3d::UnitX());
    const Vec3d y = moved(View::kIso, Vec3d::UnitY());
    const Vec3d z = moved(View::kIso, Vec3d::UnitZ());
    EXPECT_NEAR(z.x(), 0, 1e-12);
    EXPECT_LT(z.y(), 0);
    EXPECT_GT(x.x(), 0);  // lower right
    EXPECT_GT(x.y(), 0);
    EXPECT_GT(y.x(), 0);  // upper right
    EXPECT_LT(y.y(), 0);
}

TEST(Camera, ProjectAndUnprojectAreInverse) {
    Camera c = Camera::preset(View::kIso);
    c.set_frame(37.5, 100, 80);
    const Vec3d p(0.3, -1.2, 2.5);
    const Vec3d q = c.project(p);
    EXPECT_TRUE(c.unproject(q.x(), q.y(), q.z()).isApprox(p, 1e-12));
}

TEST(Camera, FitCentresTheBoxInsideTheMargin) {
    Camera c = Camera::preset(View::kFront);
    // World x in [0, 4], z in [0, 1] into 200 x 100 with 10 px margins: width-limited.
    c.fit(0, 4, 0, 1, {0, 0, 200, 100}, 10);
    EXPECT_DOUBLE_EQ(c.scale(), 45.0);
    const Vec3d lo = c.project(Vec3d(0, 0, 0)), hi = c.project(Vec3d(4, 0, 1));
    EXPECT_DOUBLE_EQ(lo.x(), 10.0);
    EXPECT_DOUBLE_EQ(hi.x(), 190.0);
    EXPECT_DOUBLE_EQ((lo.y() + hi.y()) / 2, 50.0);
    EXPECT_LT(hi.y(), lo.y());  // z up
}

TEST(Camera, BadInputsAreInvalidParameters) {
    EXPECT_THROW((void)Camera::looking(Vec3d::Zero(), Vec3d::UnitZ()), Error);
    Camera c;
    EXPECT_THROW(c.set_frame(0, 0, 0), Error);
    // Looking straight along the up hint still gives a valid frame.
    const Camera down = Camera::looking(-Vec3d::UnitZ(), Vec3d::UnitZ());
    EXPECT_NEAR(down.right().norm(), 1, 1e-12);
}
