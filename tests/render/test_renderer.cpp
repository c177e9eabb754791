// Rendering: pixels where projection says, depth order, decorations, options.
#include <gtest/gtest.h>

#include <cstdlib>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/render/font.hpp"
#include "surfgrow/render/overlay.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene_builder.hpp"

using namespace surfgrow;
using namespace surfgrow::render;

namespace {

constexpr Rgb kWhite{255, 255, 255};

// A small picture without legend, triad or scale bar: only the scene.
RenderOptions bare(View view = View::kFront) {
    RenderOptions o;
    o.width = 240;
    o.height = 180;
    o.view = view;
    o.legend = false;
    o.axes = false;
    o.scale_bar = false;
    return o;
}

Disk disk(const Vec3d& c, const Vec3d& n, double r, Rgb color) {
    return {c, n.normalized(), r, color};
}

// The pixel under a world point.
Rgb pixel_at(const Image& img, const Camera& cam, const Vec3d& p) {
    const Vec3d q = cam.project(p);
    const int x = static_cast<int>(std::floor(q.x())), y = static_cast<int>(std::floor(q.y()));
    EXPECT_TRUE(img.contains(x, y)) << "(" << p.transpose() << ") is off the picture";
    return img.contains(x, y) ? img.at(x, y) : Rgb{1, 2, 3};
}

std::size_t non_background(const Image& img, Rgb bg = kWhite) {
    return img.bytes().size() / 3 - img.count(bg);
}

// Mean position of the pixels where one channel clearly dominates (0 red, 1 green, 2 blue).
Eigen::Vector2d centroid_of(const Image& img, int channel) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const Rgb c = img.at(x, y);
            const int v[3] = {c.r, c.g, c.b};
            if (v[channel] > v[(channel + 1) % 3] + 60 && v[channel] > v[(channel + 2) % 3] + 60) {
                sum += Eigen::Vector2d(x + 0.5, y + 0.5);
                ++n;
            }
        }
    EXPECT_GT(n, 0) << "no pixels of channel " << channel;
    return n ? Eigen::Vector2d(sum / n) : Eigen::Vector2d(-1, -1);
}

ErrorCode code_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.code();
    }
    return ErrorCode::kInternal;
}

}  // namespace

TEST(Renderer, FaceOnDiskLandsWhereProjectionSaysInItsShadedColour) {
    Scene scene;
    const Rgb color{200, 120, 60};
    scene.disks.push_back(disk({0.5, 2, -1}, -Vec3d::UnitY(), 1.0, color));
    const RenderOptions o = bare();
    const Camera cam = frame_scene(scene, o);
    const Image img = render_scene(scene, o);
    ASSERT_EQ(img.width(), 240);
    ASSERT_EQ(img.height(), 180);
    const Rgb lit = shade(color, -Vec3d::UnitY(), cam, o.lighting);
    EXPECT_NE(lit, color);  // shading did something
    EXPECT_EQ(pixel_at(img, cam, {0.5, 2, -1}), lit);
    EXPECT_EQ(pixel_at(img, cam, {0.5 + 0.6, 2, -1 - 0.6}), lit);
    // Background a little outside the rim, and in the corners.
    EXPECT_EQ(pixel_at(img, cam, {0.5 + 1.08, 2, -1}), kWhite);
    EXPECT_EQ(pixel_at(img, cam, {0.5, 2, -1 + 1.08}), kWhite);
    EXPECT_EQ(img.at(0, 0), kWhite);
    EXPECT_EQ(img.at(239, 179), kWhite);
    // Its area is pi r^2 in pixels.
    const double r_px = cam.scale();
    EXPECT_NEAR(double(non_background(img)), M_PI * r_px * r_px, 0.03 * M_PI * r_px * r_px);
}

TEST(Renderer, EdgeOnDiskCoversAlmostNothing) {
    Scene face_on, edge_on;
    face_on.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, {200, 50, 50}));
    edge_on.disks.push_back(disk({0, 0, 0}, Vec3d::UnitX(), 1.0, {200, 50, 50}));
    RenderOptions o = bare();
    const double area = double(non_background(render_scene(face_on, o)));
    const double line = double(non_background(render_scene(edge_on, o)));
    EXPECT_GT(line, 0);  // drawn as a thin line (min_disk_thickness)
    EXPECT_LT(line, 0.03 * area);
    o.min_disk_thickness = 0;
    EXPECT_EQ(non_background(render_scene(edge_on, o)), 0u);
}

TEST(Renderer, NearerDiskHidesFartherOneWhateverTheOrder) {
    const Rgb far_color{220, 40, 40}, near_color{40, 40, 220};
    const Disk far_disk = disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, far_color);
    const Disk near_disk = disk({0, -1, 0}, -Vec3d::UnitY(), 0.5, near_color);
    RenderOptions o = bare();
    o.lighting.fog = 0;
    for (bool near_first : {false, true}) {
        Scene scene;
        scene.disks = near_first ? std::vector<Disk>{near_disk, far_disk}
                                 : std::vector<Disk>{far_disk, near_disk};
        const Camera cam = frame_scene(scene, o);
        const Image img = render_scene(scene, o);
        EXPECT_EQ(pixel_at(img, cam, {0, 0, 0}),
                  shade(near_color, -Vec3d::UnitY(), cam, o.lighting));
        EXPECT_EQ(pixel_at(img, cam, {0.75, 0, 0}),
                  shade(far_color, -Vec3d::UnitY(), cam, o.lighting));
    }
}

TEST(Renderer, CrossingDisksOccludeEachOtherPerPixel) {
    // B leans back above the crossing line and forward below it: a painter's algorithm could
    // only get one half right.
    const Vec3d na = -Vec3d::UnitY(), nb = Vec3d(0, -1, 1).normalized();
    Scene scene;
    scene.disks = {disk({0, 0, 0}, na, 1.0, {220, 60, 60}),
                   disk({0, 0, 0}, nb, 1.0, {60, 60, 220})};
    const RenderOptions o = bare();
    const Camera cam = frame_scene(scene, o);
    const Image img = render_scene(scene, o);
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 0.4}), shade({220, 60, 60}, na, cam, o.lighting));
    EXPECT_EQ(pixel_at(img, cam, {0, 0, -0.4}), shade({60, 60, 220}, nb, cam, o.lighting));
}

TEST(Renderer, NormalsAreDrawnAlongTheNormal) {
    Surface s;
    s.normal = Vec3d::UnitZ();
    s.radius = 1.0;
    SurfaceStyle style;
    style.normals = true;
    style.normal_length = 2.0;
    const Scene scene = scene_from_surfaces({s}, style);
    RenderOptions o = bare();  // the disk is edge-on, its normal points up the screen
    o.line_width = 3;
    o.normal_min_radius = 0;  // every normal: they are framed too
    const Camera cam = frame_scene(scene, o);
    const Image img = render_scene(scene, o);
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 1.0}), kNormalRed);
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 1.9}), kNormalRed);
    EXPECT_EQ(pixel_at(img, cam, {0.3, 0, 1.0}), kWhite);  // beside the line
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 2.06}), kWhite);   // not past its tip
}

TEST(Renderer, PointsLieBeneathDisksButShowElsewhere) {
    const Rgb disk_color{230, 200, 90};
    const Rgb on{0, 160, 0}, outside{0, 0, 200}, in_front{200, 0, 200};
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, disk_color));
    scene.point_depth_bias = 0.1;
    scene.points = {{Vec3f(0, 0, 0), on},                   // on the disk: beneath it
                    {Vec3f(1.25f, 0, 0), outside},          // beside it
                    {Vec3f(0.5f, -0.5f, 0.3f), in_front}};  // well in front of it
    RenderOptions o = bare();
    o.point_size = 5;
    const Camera cam = frame_scene(scene, o);
    const Image img = render_scene(scene, o);
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 0}), shade(disk_color, -Vec3d::UnitY(), cam, o.lighting));
    EXPECT_EQ(pixel_at(img, cam, {1.25, 0, 0}), outside);
    EXPECT_EQ(pixel_at(img, cam, {0.5, -0.5, 0.3}), in_front);
}

TEST(Renderer, ViewPresetsPutAxesOnTheExpectedSide) {
    Scene scene;
    const Vec3d n = Vec3d(1, 1, 1).normalized();  // not edge-on in any preset
    scene.disks = {disk({0, 0, 0}, n, 0.6, {128, 128, 128}), disk({3, 0, 0}, n, 0.6, {230, 0, 0}),
                   disk({0, 3, 0}, n, 0.6, {0, 230, 0}), disk({0, 0, 3}, n, 0.6, {0, 0, 230})};
    RenderOptions o = bare();
    o.back_faces = BackFaces::kShow;
    o.outlines = false;
    auto centroids = [&](View v, Eigen::Vector2d& red, Eigen::Vector2d& green,
                         Eigen::Vector2d& blue, bool want_red, bool want_green, bool want_blue) {
        o.view = v;
        const Image img = render_scene(scene, o);
        if (want_red) red = centroid_of(img, 0);
        if (want_green) green = centroid_of(img, 1);
        if (want_blue) blue = centroid_of(img, 2);
        return frame_scene(scene, o).project(Vec3d::Zero());
    };
    Eigen::Vector2d r, g, b;
    Vec3d c = centroids(View::kFront, r, g, b, true, false, true);
    EXPECT_GT(r.x(), c.x() + 20);  // +x right
    EXPECT_LT(b.y(), c.y() - 20);  // +z up
    c = centroids(View::kSide, r, g, b, false, true, true);
    EXPECT_GT(g.x(), c.x() + 20);  // +y right
    EXPECT_LT(b.y(), c.y() - 20);
    c = centroids(View::kTop, r, g, b, true, true, false);
    EXPECT_GT(r.x(), c.x() + 20);
    EXPECT_LT(g.y(), c.y() - 20);  // +y up
    c = centroids(View::kIso, r, g, b, true, true, true);
    EXPECT_LT(b.y(), c.y() - 20);  // z up
    EXPECT_GT(r.x(), c.x() + 20);  // x lower right
    EXPECT_GT(r.y(), c.y());
    EXPECT_GT(g.x(), c.x() + 20);  // y upper right
    EXPECT_LT(g.y(), c.y());
}

TEST(Renderer, BackFacesShowGhostOrCull) {
    const Rgb color{40, 40, 220};
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, Vec3d::UnitY(), 1.0, color));  // faces away
    scene.points.push_back({Vec3f(0.5f, -0.5f, 0), {0, 0, 0}, 0});       // belongs to that disk
    RenderOptions o = bare();
    o.point_size = 5;
    const Camera cam = frame_scene(scene, o);
    const Rgb lit = shade(color, Vec3d::UnitY(), cam, o.lighting);

    o.back_faces = BackFaces::kShow;
    Image img = render_scene(scene, o);
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 0}), lit);
    EXPECT_EQ(pixel_at(img, cam, {0.5, 0, 0}), (Rgb{0, 0, 0}));  // its point

    o.back_faces = BackFaces::kGhost;
    img = render_scene(scene, o);
    const Rgb ghost = pixel_at(img, cam, {0, 0, 0});
    EXPECT_NE(ghost, lit);
    EXPECT_NE(ghost, kWhite);
    EXPECT_GT(ghost.b, ghost.r + 20);  // still its hue, lighter
    EXPECT_GT(luminance(ghost), luminance(lit));
    EXPECT_NE(pixel_at(img, cam, {0.5, 0, 0}), (Rgb{0, 0, 0}));  // its point is not drawn

    o.back_faces = BackFaces::kCull;
    EXPECT_EQ(non_background(render_scene(scene, o)), 0u);
}

TEST(Renderer, PngOfARenderDecodesToTheSamePixels) {
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, Vec3d(-1, -1, 1), 1.0, id_color(3)));
    scene.legend = "1 points -> 1 surfaces, 100.0% registered";
    RenderOptions o;
    o.width = 320;
    o.height = 200;
    const Image img = render_scene(scene, o);
    std::stringstream png;
    write_png(img, png);
    png.seekg(0);
    const Image back = read_png(png);
    EXPECT_EQ(back.width(), 320);
    EXPECT_EQ(back.height(), 200);
    EXPECT_TRUE(back == img);
}

TEST(Renderer, LegendBandHasText) {
    ASSERT_TRUE(Font::find_default()) << "no font: install fonts-dejavu-core";
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, {90, 90, 200}));
    scene.legend = "276480 points -> 5231 surfaces, 99.4% registered";
    RenderOptions o = bare();
    o.width = 800;
    o.height = 600;
    o.legend = true;
    const int band = overlay_layout(o, true).band_height;
    ASSERT_GT(band, 0);
    const Image img = render_scene(scene, o);
    // Dark text pixels in the left half of the band; nothing of the scene reaches into it.
    int dark = 0;
    for (int y = o.height - band; y < o.height; ++y)
        for (int x = 0; x < o.width / 2; ++x) dark += luminance(img.at(x, y)) < 0.5;
    EXPECT_GT(dark, 200);
    const Camera cam = frame_scene(scene, o);
    EXPECT_LT(cam.project(Vec3d(0, 0, -1)).y(), o.height - band);
}

TEST(Renderer, AxisTriadAndScaleBarDrawInTheBand) {
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, {90, 90, 200}));
    RenderOptions o = bare();
    o.axes = true;
    o.scale_bar = true;
    o.units.push_back('m');  // (= "m" trips a false GCC 12 -Wrestrict)
    const Image img = render_scene(scene, o);
    const int band = overlay_layout(o, false).band_height;
    int ink = 0;
    for (int y = o.height - band; y < o.height; ++y)
        for (int x = o.width / 2; x < o.width; ++x) ink += img.at(x, y) != kWhite;
    EXPECT_GT(ink, 50);
}

// The bar is as long as its length in the scene: measured against a disk of known diameter in a
// front view (square to the view, so true), and its length a round number (1, 2 or 5 x 10^k).
TEST(Renderer, ScaleBarIsTrueToTheScene) {
    for (const double radius : {0.3, 1.0, 7.0}) {
        Scene scene;
        scene.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), radius, {90, 90, 200}));
        RenderOptions o = bare();
        o.width = 800;
        o.height = 600;
        o.scale_bar = true;
        const Image img = render_scene(scene, o);
        // The disk's widest row above the band (it is all the scene holds): its diameter.
        const int band = overlay_layout(o, false).band_height;
        int disk_px = 0;
        for (int y = 0; y < img.height() - band; ++y) {
            int run = 0;
            for (int x = 0; x < img.width(); ++x) run += img.at(x, y) != kWhite;
            disk_px = std::max(disk_px, run);
        }
        const double px_per_unit = disk_px / (2 * radius);
        // The bar: the longest run of dark pixels in a row of the band (no font: o.units is empty
        // and the label's digits are narrower than any bar).
        int bar_px = 0;
        for (int y = o.height - band; y < o.height; ++y) {
            int run = 0;
            for (int x = 0; x < img.width(); ++x) {
                run = luminance(img.at(x, y)) < 0.5 ? run + 1 : 0;
                bar_px = std::max(bar_px, run);
            }
        }
        // The bar's length: the longest round number (1, 2 or 5 x 10^k) up to 12 % of the width.
        const double most = 0.12 * o.width / px_per_unit;
        const double decade = std::pow(10.0, std::floor(std::log10(most)));
        const double expected = 5 * decade <= most   ? 5 * decade
                                : 2 * decade <= most ? 2 * decade
                                                     : decade;
        // Within 3 pixels at each end of the bar and of the disk.
        EXPECT_NEAR(bar_px / px_per_unit, expected, expected * (6.0 / bar_px + 6.0 / disk_px))
            << "radius " << radius << ": bar " << bar_px << " px, disk " << disk_px << " px";
        // A useful size: between 5 % and 12 % of the picture's width.
        EXPECT_GE(bar_px, 0.05 * o.width - 3) << "radius " << radius;
        EXPECT_LE(bar_px, 0.12 * o.width + 3) << "radius " << radius;
    }
}

TEST(Renderer, EmptySceneIsBackgroundOnly) {
    const Scene empty;
    RenderOptions o = bare();
    o.background = {10, 20, 30};
    const Image img = render_scene(empty, o);
    EXPECT_EQ(img.width(), 240);
    EXPECT_EQ(img.count({10, 20, 30}), 240u * 180u);
    // With every decoration on it still renders (the triad is all there is).
    const Image decorated = render_scene(empty, RenderOptions{});
    EXPECT_EQ(decorated.width(), 1600);
    EXPECT_EQ(decorated.height(), 1200);
}

TEST(Renderer, SkipsNonFiniteInput) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Scene scene;
    scene.disks = {
        disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, {200, 0, 0}),
        {Vec3d(nan, 0, 0), -Vec3d::UnitY(), 1.0, {0, 200, 0}},
        {Vec3d(0, 0, 0), Vec3d(nan, 0, 0), 1.0, {0, 200, 0}},
        {Vec3d(0, 0, 0), Vec3d::Zero(), 1.0, {0, 200, 0}},
        {Vec3d(5, 0, 0), -Vec3d::UnitY(), std::numeric_limits<double>::infinity(), {0, 200, 0}}};
    scene.points = {{Vec3f(std::nanf(""), 0, 0), {0, 0, 0}, -1}};
    scene.lines = {{Vec3d(0, 0, 0), Vec3d(nan, 0, 0), kNormalRed, -1}};
    const RenderOptions o = bare();
    const Camera cam = frame_scene(scene, o);
    EXPECT_NEAR(cam.scale(), frame_scene(Scene{{scene.disks[0]}, {}, {}, "", 0}, o).scale(), 1e-9);
    const Image img = render_scene(scene, o);
    EXPECT_EQ(pixel_at(img, cam, {0, 0, 0}), shade({200, 0, 0}, -Vec3d::UnitY(), cam, o.lighting));
}

TEST(Renderer, SameResultForAnyThreadCountAndTileOrder) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    Scene scene;
    for (int i = 0; i < 3000; ++i)
        scene.disks.push_back(
            disk({u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, 0.05, id_color(i)));
    for (int i = 0; i < 20000; ++i)
        scene.points.push_back(
            {Vec3f(float(u(rng)), float(u(rng)), float(u(rng))), id_color(i), -1});
    for (int i = 0; i < 300; ++i)
        scene.lines.push_back(
            {scene.disks[std::size_t(i)].center,
             scene.disks[std::size_t(i)].center + 0.1 * scene.disks[std::size_t(i)].normal,
             kNormalRed, i});
    scene.legend = "determinism";
    RenderOptions o;
    o.width = 400;
    o.height = 300;
    o.threads = 1;
    const Image one = render_scene(scene, o);
    o.threads = 3;
    EXPECT_TRUE(render_scene(scene, o) == one);
}

TEST(Renderer, FramingFillsThePictureWithinTheMargin) {
    Scene scene;
    scene.disks = {disk({-2, 0, -1}, -Vec3d::UnitY(), 0.2, {200, 0, 0}),
                   disk({2, 0, 1}, -Vec3d::UnitY(), 0.2, {200, 0, 0})};
    const RenderOptions o = bare();
    const Image img = render_scene(scene, o);
    int x0 = o.width, x1 = -1;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x)
            if (img.at(x, y) != kWhite) x0 = std::min(x0, x), x1 = std::max(x1, x);
    const double margin = o.margin * std::min(o.width, o.height);
    EXPECT_NEAR(x0, margin, 1.5);
    EXPECT_NEAR(x1 + 1, o.width - margin, 1.5);
}

TEST(Renderer, InvalidOptionsAreInvalidParameters) {
    const Scene scene;
    auto with = [&](auto change) {
        RenderOptions o;
        change(o);
        return code_of([&] { (void)render_scene(scene, o); });
    };
    EXPECT_EQ(with([](RenderOptions& o) { o.width = 0; }), ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.height = -3; }), ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.width = 100000; }), ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.width = o.height = 16384; }),
              ErrorCode::kInvalidParameter);  // over 64 Mpixel
    EXPECT_EQ(with([](RenderOptions& o) { o.supersample = 0; }), ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.margin = 0.9; }), ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.point_size = std::nan(""); }),
              ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.lighting.direction = Vec3d::Zero(); }),
              ErrorCode::kInvalidParameter);
    EXPECT_EQ(with([](RenderOptions& o) { o.font_file = "/nonexistent/font.ttf"; }),
              ErrorCode::kCannotOpen);
}

TEST(Renderer, APictureBeyondTheMemoryBudgetIsRefusedBeforeDrawing) {
    // 10^5 disks need about 25 MB to draw: over a 4 MB budget, a clear error, not an OOM kill.
    Scene scene;
    for (int i = 0; i < 100000; ++i)
        scene.disks.push_back({Vec3d(i % 300, i / 300, 0), Vec3d::UnitZ(), 0.5, {1, 2, 3}});
    ::setenv("SURFGROW_MEMORY_LIMIT", "4M", 1);
    try {
        (void)render_scene(scene, bare());
        ADD_FAILURE() << "drawn";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge);
        EXPECT_NE(std::string(e.what()).find("drawing 100000 disks"), std::string::npos)
            << e.what();
    }
    ::unsetenv("SURFGROW_MEMORY_LIMIT");
    EXPECT_EQ(render_scene(scene, bare()).width(), bare().width);
}

TEST(Renderer, SupersamplingLevelsAgreeInTheInterior) {
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, {100, 150, 200}));
    RenderOptions o = bare();
    const Camera cam = frame_scene(scene, o);
    for (int ss = 1; ss <= 4; ++ss) {
        o.supersample = ss;
        const Image img = render_scene(scene, o);
        EXPECT_EQ(pixel_at(img, cam, {0.2, 0, 0.3}),
                  shade({100, 150, 200}, -Vec3d::UnitY(), cam, o.lighting))
            << "supersample " << ss;
    }
}

TEST(Renderer, FramesSurfacesNotStrayPointsButPointsAlone) {
    Scene scene;
    scene.disks.push_back(disk({0, 0, 0}, -Vec3d::UnitY(), 1.0, {200, 0, 0}));
    const RenderOptions o = bare();
    const double scale = frame_scene(scene, o).scale();
    scene.points.push_back({Vec3f(100, 0, 0), kUnassignedGrey, -1});  // a stray far return
    EXPECT_DOUBLE_EQ(frame_scene(scene, o).scale(), scale);

    Scene points_only;
    points_only.points = {{Vec3f(-3, 0, -1), {0, 0, 0}, -1}, {Vec3f(3, 0, 1), {0, 0, 0}, -1}};
    const Camera cam = frame_scene(points_only, o);
    const double margin = o.margin * std::min(o.width, o.height);
    EXPECT_NEAR(cam.project(Vec3d(-3, 0, -1)).x(), margin, 1e-9);
    EXPECT_NEAR(cam.project(Vec3d(3, 0, 1)).x(), o.width - margin, 1e-9);
}

TEST(Renderer, FarFromTheOriginKeepsDepthOrder) {
    // Georeferenced-size coordinates: two disks 1 mm apart in depth, 1e6 m from the origin.
    const Vec3d base(4.5e5, 5.2e6, 300);
    Scene scene;
    scene.disks = {disk(base, -Vec3d::UnitY(), 0.05, {220, 40, 40}),
                   disk(base - Vec3d(0, 0.001, 0), -Vec3d::UnitY(), 0.02, {40, 40, 220})};
    RenderOptions o = bare();
    o.lighting.fog = 0;
    const Camera cam = frame_scene(scene, o);
    const Image img = render_scene(scene, o);
    EXPECT_EQ(pixel_at(img, cam, base), shade({40, 40, 220}, -Vec3d::UnitY(), cam, o.lighting));
    EXPECT_EQ(pixel_at(img, cam, base + Vec3d(0.035, 0, 0)),
              shade({220, 40, 40}, -Vec3d::UnitY(), cam, o.lighting));
}
