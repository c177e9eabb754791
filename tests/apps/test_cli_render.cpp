// End-to-end tests of `surfgrow render`: the real binary on a grown box, its pictures checked
// pixel by pixel against where the renderer's camera puts the disks.
#include <gtest/gtest.h>

#include <sstream>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/render/group_colors.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene_builder.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_surfgrow;

constexpr render::Rgb kWhite{255, 255, 255};

render::Image read_picture(const fs::path& file) {
    return render::decode_png(test::read_bytes(file));
}

// Hue in [0, 1) and saturation of a colour.
std::pair<double, double> hue_saturation(render::Rgb c) {
    const double r = c.r / 255.0, g = c.g / 255.0, b = c.b / 255.0;
    const double hi = std::max({r, g, b}), lo = std::min({r, g, b}), d = hi - lo;
    if (d <= 0) return {0.0, 0.0};
    double h = hi == r ? (g - b) / d : hi == g ? 2 + (b - r) / d : 4 + (r - g) / d;
    h /= 6;
    if (h < 0) h += 1;
    return {h, d / hi};
}

double hue_distance(double a, double b) {
    const double d = std::abs(a - b);
    return std::min(d, 1 - d);
}

class CliRender : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir();
        box_ = new test::GrownBox(test::grow_box(dir_->path()));
    }
    static void TearDownTestSuite() {
        delete box_;
        delete dir_;
    }
    // `surfgrow render OUT <args>`, expected to succeed.
    static fs::path render(const std::string& name, const std::string& args) {
        const fs::path png = dir_->path() / name;
        const test::CliRun r =
            run_surfgrow(cat({"render ", quoted(box_->out), " -o ", quoted(png), " ", args}));
        EXPECT_EQ(r.code, 0) << r.out;
        return png;
    }
    static render::Scene scene() {
        render::Scene s = render::scene_from_surfaces(box_->result.surfaces);
        s.legend = render::legend_line(box_->result.stats.points_in, box_->result.stats.surfaces,
                                       box_->result.stats.registered_fraction());
        return s;
    }
    static inline test::TempDir* dir_ = nullptr;
    static inline test::GrownBox* box_ = nullptr;
};

TEST_F(CliRender, DefaultPictureIsTheOneGrowDrew) {
    const fs::path png = render("default.png", "-q");
    EXPECT_EQ(test::read_bytes(png), test::read_bytes(box_->out / "surfaces.png"));
}

// In every view: the requested size, and the pixel under the centre of every disk that faces
// the viewer (drawn solid) is not background, where the renderer's own framing puts it.
TEST_F(CliRender, EveryViewDrawsTheDisksWhereTheCameraProjectsThem) {
    const render::Scene s = scene();
    std::vector<std::string> pictures;
    for (const char* view : {"front", "side", "top", "iso"}) {
        SCOPED_TRACE(view);
        const render::Image image =
            read_picture(render(cat({view, ".png"}), cat({"--view ", view, " --size 480x360"})));
        ASSERT_EQ(image.width(), 480);
        ASSERT_EQ(image.height(), 360);
        render::RenderOptions options;
        options.width = 480;
        options.height = 360;
        options.view = render::parse_view(view);
        const render::Camera camera = render::frame_scene(s, options);
        std::size_t checked = 0;
        for (const render::Disk& d : s.disks) {
            // Not edge-on; seen from the front (solid) or from behind (ghosted, still drawn).
            if (d.radius <= 0 || std::abs(d.normal.dot(camera.forward())) < 0.5) continue;
            const Vec3d p = camera.project(d.center);
            const int x = static_cast<int>(p.x()), y = static_cast<int>(p.y());
            ASSERT_TRUE(image.contains(x, y)) << "disk centre off the picture at " << x << "," << y;
            EXPECT_NE(image.at(x, y), kWhite) << "disk centre at " << x << "," << y;
            ++checked;
        }
        EXPECT_GT(checked, 50u);
        EXPECT_EQ(image.at(1, 1), kWhite);  // the margin stays background
        // The legend line is written in the band along the bottom.
        std::size_t ink = 0;
        for (int y = image.height() * 9 / 10; y < image.height(); ++y)
            for (int x = 0; x < image.width() / 2; ++x) ink += image.at(x, y).r < 120 ? 1 : 0;
        EXPECT_GT(ink, 20u);
        pictures.push_back(test::read_bytes(dir_->path() / cat({view, ".png"})));
    }
    for (std::size_t i = 0; i < pictures.size(); ++i)
        for (std::size_t j = i + 1; j < pictures.size(); ++j) EXPECT_NE(pictures[i], pictures[j]);
}

TEST_F(CliRender, PicturesMatchTheLibraryWithTheSameOptions) {
    // --normals --view side --size: the same bytes as render_scene with those options.
    const fs::path png = render("side-normals.png", "--view side --normals --size 640x480 -q");
    render::SurfaceStyle style;
    style.normals = true;
    render::Scene s = render::scene_from_surfaces(box_->result.surfaces, style);
    s.legend = scene().legend;
    render::RenderOptions options;
    options.width = 640;
    options.height = 480;
    options.view = render::View::kSide;
    options.units = "m";
    options.normal_min_radius = 0;  // --normals: every normal, whatever its disk's size
    options.back_faces = render::BackFaces::kShow;  // the normals face a guessed frame origin
    EXPECT_EQ(test::read_bytes(png), render::encode_png(render::render_scene(s, options)));
}

TEST_F(CliRender, NormalsAreRedLines) {
    auto red_pixels = [](const render::Image& image) {  // above the legend band (red x axis)
        std::size_t n = 0;
        for (int y = 0; y < image.height() * 9 / 10; ++y)
            for (int x = 0; x < image.width(); ++x) {
                const render::Rgb c = image.at(x, y);
                n += c.r > 150 && c.r > 2 * c.g && c.r > 2 * c.b ? 1 : 0;
            }
        return n;
    };
    const render::Image plain = read_picture(render("plain.png", "--size 640x480 --no-normals"));
    const render::Image normals = read_picture(render("normals.png", "--size 640x480 --normals"));
    EXPECT_EQ(red_pixels(plain), 0u);
    EXPECT_GT(red_pixels(normals), 200u);
    // By default only where the disks are big enough on screen (8 px): in a large picture, not
    // in a small one.
    EXPECT_GT(red_pixels(read_picture(render("auto-big.png", "--size 1600x1200"))), 200u);
    EXPECT_EQ(red_pixels(read_picture(render("auto-small.png", "--size 240x180"))),
              red_pixels(read_picture(render("none-small.png", "--size 240x180 --no-normals"))));
}

TEST_F(CliRender, PointsComeFromTheCloudWithTheirSurfaceColours) {
    const fs::path png = dir_->path() / "points.png";
    const test::CliRun r =
        run_surfgrow(cat({"render ", quoted(box_->out), " -o ", quoted(png), " --points --cloud ",
                          quoted(box_->cloud), " --size 640x480"}));
    ASSERT_EQ(r.code, 0) << r.out;
    std::size_t finite = 0;
    for (const Vec3f& p : box_->points.points) finite += is_finite(p) ? 1 : 0;
    EXPECT_NE(r.out.find(cat({std::to_string(finite), " points"})), std::string::npos) << r.out;
    const render::Image without = read_picture(render("nopoints.png", "--size 640x480"));
    const render::Image with = read_picture(png);
    ASSERT_EQ(with.width(), without.width());
    std::size_t changed = 0;
    for (int y = 0; y < with.height(); ++y)
        for (int x = 0; x < with.width(); ++x) changed += with.at(x, y) != without.at(x, y);
    EXPECT_GT(changed, 500u);
}

TEST_F(CliRender, ColourByPlaneUsesTheBoundPlanesColours) {
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    fs::copy(box_->out, out);
    // Bound planes 3 and 8 (of 9) hold the surfaces: 3 the horizontal faces, 8 the vertical ones.
    BoundPlanes planes;
    planes.stats.patches = box_->result.surfaces.size();
    planes.plane_of_patch.assign(box_->result.surfaces.size(), -1);
    for (int id = 0; id < 9; ++id) {
        BoundPlane p;
        p.polygons.push_back({{{0, 0}, {1, 0}, {0, 1}}, {}});
        for (std::size_t i = 0; i < box_->result.surfaces.size() && (id == 3 || id == 8); ++i)
            if ((std::abs(box_->result.surfaces[i].normal.z()) > 0.7) == (id == 3)) {
                p.patches.push_back(static_cast<std::uint32_t>(i));
                planes.plane_of_patch[i] = id;
            }
        planes.planes.push_back(p);
    }
    std::ostringstream planes_file;
    io::write_planes_json(planes_file, planes, box_->result.meta);
    test::write_bytes(out / "planes.json", planes_file.str());
    auto share_of_plane_hues = [&](const std::string& colour_by) {
        const fs::path png = tmp / cat({colour_by, ".png"});
        const test::CliRun r = run_surfgrow(cat({"render ", quoted(out), " -o ", quoted(png),
                                                 " --size 640x480 --color-by ", colour_by}));
        EXPECT_EQ(r.code, 0) << r.out;
        const render::Image image = read_picture(png);
        // Two bound planes that meet: the palette's first two colours, the larger plane first.
        const double h3 = hue_saturation(render::kGroupPalette[0]).first;
        const double h8 = hue_saturation(render::kGroupPalette[1]).first;
        std::size_t coloured = 0, of_planes = 0;
        for (int y = 0; y < image.height() * 9 / 10; ++y)
            for (int x = 0; x < image.width(); ++x) {
                const auto [h, sat] = hue_saturation(image.at(x, y));
                if (sat < 0.15) continue;
                ++coloured;
                of_planes += std::min(hue_distance(h, h3), hue_distance(h, h8)) < 0.04;
            }
        EXPECT_GT(coloured, 1000u);
        return double(of_planes) / double(std::max<std::size_t>(coloured, 1));
    };
    const double by_plane = share_of_plane_hues("plane");
    const double by_surface = share_of_plane_hues("surface");
    std::printf("share of the planes' two hues: %.3f by plane, %.3f by surface\n", by_plane,
                by_surface);
    EXPECT_GT(by_plane, 0.8);
    EXPECT_LT(by_surface, 0.4);
}

TEST_F(CliRender, BackFacesAreGhostedOnlyWhereTheSensorWasKnown) {
    // The box's normals face the frame origin, a guess (a world-frame cloud can have it on its
    // floor): every disk solid. The same result with a viewpoint on record: back faces ghosted.
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    fs::copy(box_->out, out);
    render::RenderOptions options;
    options.width = 640;
    options.height = 480;
    options.units = "m";
    auto drawn = [&](const std::string& png) {
        const test::CliRun r = run_surfgrow(cat(
            {"render ", quoted(out), " -o ", quoted(tmp / png), " --size 640x480 --no-normals"}));
        EXPECT_EQ(r.code, 0) << r.out;
        return test::read_bytes(tmp / png);
    };
    options.back_faces = render::BackFaces::kShow;
    const std::string shown = render::encode_png(render::render_scene(scene(), options));
    options.back_faces = render::BackFaces::kGhost;
    const std::string ghosted = render::encode_png(render::render_scene(scene(), options));
    ASSERT_NE(shown, ghosted);
    EXPECT_EQ(drawn("guessed.png"), shown);

    std::string json = test::read_bytes(out / "surfaces.json");
    const std::string from = "\"orientation\": \"frame_origin\"";
    ASSERT_NE(json.find(from), std::string::npos);
    json.replace(json.find(from), from.size(), "\"orientation\": \"viewpoint\"");
    test::write_bytes(out / "surfaces.json", json);
    EXPECT_EQ(drawn("known.png"), ghosted);
    json.replace(json.find("\"viewpoint\""), 11, "\"up\"");
    test::write_bytes(out / "surfaces.json", json);
    EXPECT_EQ(drawn("up.png"), shown);
}

TEST_F(CliRender, SameBytesForAnyThreadCount) {
    const fs::path one = render("t1.png", "--threads 1 --normals --size 800x600");
    const fs::path three = render("t3.png", "--threads 3 --normals --size 800x600");
    EXPECT_EQ(test::read_bytes(one), test::read_bytes(three));
}

// Every class of bad input: its own exit code, a message naming the problem, no picture.
TEST_F(CliRender, APictureThatWouldNotFitInMemoryIsExit8AndNoFile) {
    const fs::path png = dir_->path() / "too-big.png";
    const test::CliRun r = run_surfgrow(cat({"render ", quoted(box_->out), " -o ", quoted(png)}),
                                        "SURFGROW_MEMORY_LIMIT=100K ");
    EXPECT_EQ(r.code, 8) << r.out;
    EXPECT_NE(r.out.find("SURFGROW_MEMORY_LIMIT allows"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(png));
}

TEST_F(CliRender, BadInputsGiveTheirCodeAndWriteNoPicture) {
    test::TempDir tmp;
    fs::create_directories(tmp / "empty");
    fs::create_directories(tmp / "notresult");
    test::write_bytes(tmp / "notresult" / "surfaces.json", "{\"format\": \"something-else\"}");
    test::write_bytes(tmp / "short.xyz", "0 0 0\n1 0 0\n0 1 0\n");
    const std::string out = quoted(box_->out);
    struct Case {
        std::string name, args;
        ErrorCode code;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"missing folder", quoted(tmp / "nope"), ErrorCode::kCannotOpen, "no such folder"},
        {"folder without a result", quoted(tmp / "empty"), ErrorCode::kCannotOpen,
         "no surfaces.json"},
        {"not a result", quoted(tmp / "notresult"), ErrorCode::kMalformedInput,
         "not a surfgrow result"},
        {"size without x", out + " --size 1600", ErrorCode::kUsage, "--size"},
        {"size not numbers", out + " --size bigxsmall", ErrorCode::kUsage, "--size"},
        {"size half given", out + " --size 1600x", ErrorCode::kUsage, "--size"},
        {"size too small", out + " --size 8x8", ErrorCode::kInvalidParameter, "--size"},
        {"size too large", out + " --size 100000x1200", ErrorCode::kInvalidParameter, "--size"},
        {"unknown view", out + " --view diagonal", ErrorCode::kInvalidParameter, "diagonal"},
        {"negative threads", out + " --threads -1", ErrorCode::kInvalidParameter, "--threads"},
        {"unknown colouring", out + " --color-by colour", ErrorCode::kUsage, "--color-by"},
        {"no planes.json", out + " --color-by plane", ErrorCode::kCannotOpen, "planes.json"},
        {"points without cloud", out + " --points", ErrorCode::kUsage, "--cloud"},
        {"missing cloud", out + " --cloud " + quoted(tmp / "nope.ply"), ErrorCode::kCannotOpen,
         "nope.ply"},
        {"not the grown cloud", out + " --cloud " + quoted(tmp / "short.xyz"),
         ErrorCode::kMalformedInput, "is this the cloud that was grown"},
        {"unknown option", out + " --frobnicate", ErrorCode::kUsage, ""},
    };
    for (const Case& c : cases) {
        const fs::path png = tmp / cat({"out-", std::to_string(&c - cases.data()), ".png"});
        const test::CliRun r = run_surfgrow(cat({"render ", c.args, " -o ", quoted(png)}));
        EXPECT_EQ(r.code, static_cast<int>(c.code)) << c.name << ": " << r.out;
        EXPECT_NE(r.out.find(c.message), std::string::npos) << c.name << ": " << r.out;
        EXPECT_FALSE(fs::exists(png)) << c.name;
    }
    // No -o at all is a usage error; a failure leaves an older picture as it was.
    EXPECT_EQ(run_surfgrow(cat({"render ", out})).code, static_cast<int>(ErrorCode::kUsage));
    test::write_bytes(tmp / "old.png", "old");
    EXPECT_NE(
        run_surfgrow(cat({"render ", out, " -o ", quoted(tmp / "old.png"), " --size 8x8"})).code,
        0);
    EXPECT_EQ(test::read_bytes(tmp / "old.png"), "old");
}

// What a user sees first (issue 19): measured on the pictures' pixels above the legend band.
struct PictureStats {
    double ink = 0;             // share of the pixels that are not background
    double solid = 0;           // share of those in full colour (not ghosted, not grey)
    double palette = 0;         // share of the coloured pixels in a hue of kGroupPalette
    std::vector<double> shade;  // per palette colour holding >= 5 % of them: median brightness
                                // relative to the colour itself (its shading)
    std::size_t colours = 0;    // palette colours holding >= 1 % of the coloured pixels
};

PictureStats picture_stats(const render::Image& image) {
    PictureStats st;
    std::size_t ink = 0, coloured = 0, in_palette = 0, all = 0;
    std::vector<std::vector<double>> shade(render::kGroupPalette.size());
    for (int y = 0; y < image.height() * 9 / 10; ++y)
        for (int x = 0; x < image.width(); ++x) {
            ++all;
            const render::Rgb c = image.at(x, y);
            ink += std::min({c.r, c.g, c.b}) < 245;
            const auto [h, sat] = hue_saturation(c);
            if (sat < 0.25) continue;
            ++coloured;
            for (std::size_t k = 0; k < render::kGroupPalette.size(); ++k) {
                const render::Rgb p = render::kGroupPalette[k];
                if (hue_distance(h, hue_saturation(p).first) >= 0.02) continue;
                ++in_palette;
                shade[k].push_back(double(std::max({c.r, c.g, c.b})) / std::max({p.r, p.g, p.b}));
                break;
            }
        }
    st.ink = double(ink) / double(all);
    st.solid = double(coloured) / double(std::max<std::size_t>(ink, 1));
    st.palette = double(in_palette) / double(std::max<std::size_t>(coloured, 1));
    for (auto& v : shade) {
        st.colours += double(v.size()) >= 0.01 * double(coloured);
        if (double(v.size()) >= 0.05 * double(coloured)) {
            std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
            st.shade.push_back(v[v.size() / 2]);
        }
    }
    return st;
}

// `surfgrow render OUT --frame all` into `png`: the same result framed on everything.
PictureStats framed_on_everything(const fs::path& out, const fs::path& png) {
    const test::CliRun r =
        run_surfgrow(cat({"render ", quoted(out), " --frame all -q -o ", quoted(png)}));
    EXPECT_EQ(r.code, 0) << r.out;
    return picture_stats(read_picture(png));
}

void print_stats(const char* what, const PictureStats& st) {
    std::printf("%s: ink %.3f, solid %.3f, palette %.3f, %zu colours, shades", what, st.ink,
                st.solid, st.palette, st.colours);
    for (const double s : st.shade) std::printf(" %.2f", s);
    std::printf("\n");
}

TEST(Pictures, TheDemoShowsTheStructureByPlaneAndACornerWithNormals) {
    test::TempDir tmp;
    const fs::path out = tmp / "demo";
    const test::CliRun r = run_surfgrow(cat({"demo --poses 1 -q -o ", quoted(out)}));
    ASSERT_EQ(r.code, 0) << r.out;
    // The overview: the channel fills the picture (framed with the floor strips far below it,
    // it covered 14 %), in the bound planes' colours (coloured per surface: 36 % of the coloured
    // pixels in the palette's hues; the ghosted near walls blend hues).
    const PictureStats overview = picture_stats(read_picture(out / "surfaces.png"));
    print_stats("overview", overview);
    EXPECT_GT(overview.ink, 0.35);
    EXPECT_GT(overview.palette, 0.55);
    EXPECT_GE(overview.colours, 4u);  // several faces, each in its plane's colour (4-6 seen)
    EXPECT_LT(framed_on_everything(out, tmp / "all.png").ink, 0.8 * overview.ink);
    // The close-up: three faces meeting, each in its colour, shaded differently by its
    // orientation, with the normals drawn.
    const render::Image corner = read_picture(out / "corner.png");
    const PictureStats close = picture_stats(corner);
    print_stats("corner", close);
    EXPECT_GT(close.palette, 0.75);
    ASSERT_GE(close.shade.size(), 3u);
    EXPECT_GT(*std::max_element(close.shade.begin(), close.shade.end()) -
                  *std::min_element(close.shade.begin(), close.shade.end()),
              0.15);
    std::size_t red = 0;
    for (int y = 0; y < corner.height() * 9 / 10; ++y)
        for (int x = 0; x < corner.width(); ++x) {
            const render::Rgb c = corner.at(x, y);
            red += c.r > 150 && c.r > 2 * c.g && c.r > 2 * c.b;
        }
    EXPECT_GT(red, 2000u);
    // `render --close-up` draws the same picture.
    const fs::path again = tmp / "corner.png";
    ASSERT_EQ(run_surfgrow(cat({"render ", quoted(out), " --close-up -q -o ", quoted(again)})).code,
              0);
    EXPECT_EQ(test::read_bytes(again), test::read_bytes(out / "corner.png"));
}

TEST(Pictures, StrayPatchesFarFromTheStructureDoNotShrinkIt) {
    // A 1 m plate on a 5 mm grid, and 40 m away a small patch with 1 % of the points.
    test::TempDir tmp;
    PointCloud cloud;
    std::mt19937_64 rng(5);
    std::normal_distribution<float> noise(0.0f, 0.0005f);
    for (int i = 0; i <= 200; ++i)
        for (int j = 0; j <= 200; ++j)
            cloud.points.emplace_back(0.005f * float(i), 0.005f * float(j), 1.0f + noise(rng));
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j)
            cloud.points.emplace_back(40.0f + 0.005f * float(i), 0.005f * float(j), noise(rng));
    io::write_cloud(tmp / "stray.ply", cloud);
    const test::CliRun r = run_surfgrow(cat({"grow ", quoted(tmp / "stray.ply"), " -q -o ",
                                             quoted(tmp / "out"), " --viewpoint 0.5,0.5,3m"}));
    ASSERT_EQ(r.code, 0) << r.out;
    const PictureStats bulk = picture_stats(read_picture(tmp / "out" / "surfaces.png"));
    const PictureStats all = framed_on_everything(tmp / "out", tmp / "all.png");
    print_stats("bulk", bulk);
    print_stats("all", all);
    EXPECT_GT(bulk.ink, 0.3);
    EXPECT_LT(all.ink, 0.05);
}

TEST(Pictures, RealTiltedStepsShowTheirFacesInColours) {
    const auto real = test::real_data_dir();
    if (!real) GTEST_SKIP() << "../shared/data/real is not here";
    const fs::path steps = *real / "plane_seg" / "tilted-steps.pcd";
    if (!fs::exists(steps)) GTEST_SKIP() << steps << " is not here";
    test::TempDir tmp;
    const test::CliRun r = run_surfgrow(cat({"grow ", quoted(steps),
                                             " -q --no-occupancy --no-octomap "
                                             "--no-collision --no-coverage -o ",
                                             quoted(tmp / "out")}));
    ASSERT_EQ(r.code, 0) << r.out;
    const PictureStats bulk = picture_stats(read_picture(tmp / "out" / "surfaces.png"));
    const PictureStats all = framed_on_everything(tmp / "out", tmp / "all.png");
    print_stats("steps", bulk);
    EXPECT_GE(bulk.ink, all.ink);
    EXPECT_GT(bulk.palette, 0.75);
    EXPECT_GE(bulk.colours, 5u);  // faces in several colours, not one
    // The cloud has no viewpoint and its frame origin lies on its floor: the normals facing the
    // origin flip across the floor, so ghosting "back faces" paled half of it (solid 0.47).
    EXPECT_GT(bulk.solid, 0.8);
    // Shaded by orientation: the main colours' brightness differs (floor, risers, walls).
    ASSERT_GE(bulk.shade.size(), 2u);
    EXPECT_GT(*std::max_element(bulk.shade.begin(), bulk.shade.end()) -
                  *std::min_element(bulk.shade.begin(), bulk.shade.end()),
              0.15);
}

}  // namespace
}  // namespace surfgrow
