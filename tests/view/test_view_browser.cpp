// The `surfgrow view` page in a real browser: Debian's Chromium, headless, software WebGL
// (SwiftShader), opened from disk. The scene must render (pixels where the surfaces project),
// the switches must work, and there must be no console error and no request beyond the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "headless_chromium.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/view/viewer_html.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::HeadlessChromium;

constexpr int kWidth = 1000, kHeight = 700;
constexpr render::Rgb kWhite{255, 255, 255};

struct Pixel {
    int x, y;
};

class ViewInBrowser : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        chromium_ = HeadlessChromium::find();
        if (!chromium_) return;
        dir_ = new test::TempDir();
        // The sensor on record, so back faces start ghosted (surfaces_picture.hpp, back_faces_for).
        box_ = new test::GrownBox(test::grow_box(dir_->path(), " --viewpoint 0,0,0m"));
        write_page(box_->out, "plain.html");
        test::GrownBox layered = *box_;
        layered.out = dir_->path() / "layered";
        fs::copy(box_->out, layered.out);
        goals_ = test::write_layer_fixtures(layered);
        write_page(layered.out, "layers.html");
    }
    static void TearDownTestSuite() {
        delete box_;
        delete dir_;
    }
    void SetUp() override {
        if (!chromium_)
            GTEST_SKIP() << "Chromium is not installed (Debian: apt-get install chromium, or "
                            "scripts/install-deps.sh test); the viewer's browser tests need it";
        scratch_ = std::make_unique<test::TempDir>();
        browser_ =
            std::make_unique<HeadlessChromium>(*chromium_, scratch_->path(), kWidth, kHeight);
    }
    void TearDown() override {
        if (!browser_) return;
        EXPECT_TRUE(browser_->errors().empty()) << errors();
        browser_.reset();
    }

    static void write_page(const fs::path& out, const char* name) {
        const test::CliRun r = test::run_surfgrow(
            cat({"view ", test::quoted(out), " -o ", test::quoted(dir_->path() / name), " --cloud ",
                 test::quoted(box_->cloud)}));
        ASSERT_EQ(r.code, 0) << r.out;
    }
    // Opens a page and waits until it has drawn its first frame (or reported an error).
    void open(const char* name) {
        url_ = "file://" + (dir_->path() / name).string();
        browser_->open(url_);
        ASSERT_TRUE(
            browser_->wait_until("window.surfgrowView !== undefined && (surfgrowView.ready || "
                                 "surfgrowView.error !== null)",
                                 std::chrono::seconds(120)))
            << "the page never became ready\n"
            << browser_->log();
        ASSERT_EQ(browser_->evaluate("surfgrowView.error"), json()) << errors();
    }
    std::string errors() const {
        std::string all;
        for (const std::string& e : browser_->errors()) all += e + "\n";
        return all;
    }
    // After a change: two animation frames, so the page has drawn it.
    void settle() {
        browser_->evaluate(
            "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(1))))");
    }
    void click(const std::string& id) {
        ASSERT_EQ(browser_->evaluate(cat({"(() => { const e = document.getElementById('", id,
                                          "'); if (!e || e.disabled) return false; e.click(); "
                                          "return true; })()"})),
                  true)
            << id;
        settle();
    }
    // The page as it is; also kept in $SURFGROW_SCREENSHOT_DIR when set, to look at.
    render::Image screenshot() {
        const std::string png = browser_->screenshot_png();
        if (const char* keep = std::getenv("SURFGROW_SCREENSHOT_DIR"); keep && *keep) {
            const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
            test::write_bytes(
                fs::path(keep) / cat({info->name(), "-", std::to_string(shots_++), ".png"}), png);
        }
        const render::Image image = render::decode_png(png);
        EXPECT_EQ(image.width(), kWidth);
        EXPECT_EQ(image.height(), kHeight);
        return image;
    }
    // Where a point (file coordinates) lands, if it is in the window and clear of the panel.
    std::optional<Pixel> project(const Vec3d& p) {
        const json xy = browser_->evaluate(
            cat({"surfgrowView.project(", num(p.x()), ",", num(p.y()), ",", num(p.z()), ")"}));
        const json panel = browser_->evaluate(
            "(() => { const r = document.getElementById('sg-panel').getBoundingClientRect(); "
            "return [r.left, r.top, r.right, r.bottom]; })()");
        const double x = xy[0], y = xy[1];
        if (!(x >= 2 && y >= 2 && x < kWidth - 2 && y < kHeight - 2)) return std::nullopt;
        if (x < double(panel[2]) + 4 && y < double(panel[3]) + 4) return std::nullopt;
        return Pixel{static_cast<int>(x), static_cast<int>(y)};
    }
    // Disk centres that face the starting view (from the front-right-above corner).
    std::vector<Pixel> facing_disk_centres() {
        const Vec3d towards_viewer = Vec3d(1, -1, 1).normalized();
        std::vector<Pixel> pixels;
        const auto& surfaces = box_->result.surfaces;
        for (std::size_t i = 0; i < surfaces.size(); i += 7) {
            const Surface& s = surfaces[i];
            if (s.normal.dot(towards_viewer) < 0.5) continue;
            const Vec3d centre = s.home - s.normal * s.normal.dot(s.home - s.centroid);
            if (const auto px = project(centre)) pixels.push_back(*px);
        }
        return pixels;
    }
    void expect_only_the_file_was_requested() {
        for (const std::string& r : browser_->requests())
            EXPECT_TRUE(r == url_ || r.rfind("data:", 0) == 0) << "the page requested " << r;
    }

    static inline std::optional<fs::path> chromium_;
    static inline test::TempDir* dir_ = nullptr;
    static inline test::GrownBox* box_ = nullptr;
    static inline std::size_t goals_ = 0;
    std::unique_ptr<test::TempDir> scratch_;
    std::unique_ptr<HeadlessChromium> browser_;
    std::string url_;
    int shots_ = 0;
};

std::size_t non_white(const render::Image& image) {
    std::size_t n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) n += image.at(x, y) != kWhite;
    return n;
}

TEST_F(ViewInBrowser, SurfacesDrawWhereTheyProjectAndSwitchOff) {
    open("plain.html");
    expect_only_the_file_was_requested();
    EXPECT_EQ(browser_->evaluate("surfgrowView.layers"), json({"cloud", "surfaces", "normals"}));
    // Absent layers are listed, switched off and greyed.
    EXPECT_EQ(browser_->evaluate("document.getElementById('sg-layer-planes').disabled && "
                                 "document.getElementById('sg-layer-path').disabled"),
              true);
    EXPECT_EQ(browser_->evaluate("surfgrowView.frames > 0"), true);

    const render::Image shown = screenshot();
    EXPECT_EQ(shown.at(kWidth - 3, kHeight - 3), kWhite);  // background around the scene
    const std::vector<Pixel> centres = facing_disk_centres();
    ASSERT_GT(centres.size(), 20u);
    for (const Pixel& p : centres)
        EXPECT_NE(shown.at(p.x, p.y), kWhite) << "no disk at " << p.x << "," << p.y;

    // Surfaces off (the cloud starts off): nothing left where the disks were.
    click("sg-layer-surfaces");
    EXPECT_EQ(browser_->evaluate("surfgrowView.visible('surfaces')"), false);
    const render::Image hidden = screenshot();
    for (const Pixel& p : centres)
        EXPECT_EQ(hidden.at(p.x, p.y), kWhite) << "still drawn at " << p.x << "," << p.y;

    // The cloud on: the raw points appear, but those of the near walls (seen from behind,
    // ghosted) only once back faces are shown.
    click("sg-layer-cloud");
    const std::size_t far_points = non_white(screenshot());
    EXPECT_GT(far_points, non_white(hidden) + 5000);
    click("sg-back-show");
    EXPECT_GT(non_white(screenshot()), far_points + 5000);
    // Normals and hiding back faces draw without errors.
    click("sg-layer-normals");
    click("sg-back-hide");
    EXPECT_TRUE(browser_->errors().empty()) << errors();
}

TEST_F(ViewInBrowser, BoundPlanesAndCoveragePathDraw) {
    open("layers.html");
    expect_only_the_file_was_requested();
    // The first view: surfaces coloured by bound plane, the planes on, the path off (it would
    // hide the surfaces).
    EXPECT_EQ(browser_->evaluate("surfgrowView.visible('planes') && !surfgrowView.visible('path')"),
              true);
    EXPECT_EQ(browser_->evaluate("document.getElementById('sg-colour-1').checked"), true);
    click("sg-layer-surfaces");  // leave the planes and the path alone in the picture
    click("sg-layer-path");

    const io::StoredPlanes planes = io::read_planes_json(dir_->path() / "layered" / "planes.json");
    std::vector<Pixel> plane_pixels, goal_pixels;
    for (const BoundPlane& p : planes.planes.planes)
        if (const auto px = project(p.centroid + planes.meta.offset)) plane_pixels.push_back(*px);
    const io::StoredCoverage coverage =
        io::read_coverage_json(dir_->path() / "layered" / "coverage.json");
    for (const CoverageGoal& g : coverage.plan.goals)
        if (const auto px = project(g.position + coverage.meta.offset)) goal_pixels.push_back(*px);
    EXPECT_GE(plane_pixels.size(), 4u);
    EXPECT_EQ(goal_pixels.size(), goals_);

    const render::Image both = screenshot();
    for (const Pixel& p : plane_pixels) EXPECT_NE(both.at(p.x, p.y), kWhite);
    for (const Pixel& p : goal_pixels) EXPECT_NE(both.at(p.x, p.y), kWhite);

    click("sg-layer-planes");
    const render::Image path_only = screenshot();
    // Goals take the path's colours: from green (first) to purple (last).
    const Vec3d first(26, 158, 51), last(140, 31, 179);
    for (const Pixel& p : goal_pixels) {
        const render::Rgb px = path_only.at(p.x, p.y);
        const Vec3d c(px.r, px.g, px.b);
        const double t =
            std::clamp((c - first).dot(last - first) / (last - first).squaredNorm(), 0.0, 1.0);
        EXPECT_LT((c - (first + t * (last - first))).norm(), 40.0)
            << "not a path colour at " << p.x << "," << p.y << ": " << c.transpose();
    }
    click("sg-layer-path");
    const render::Image none = screenshot();
    for (const Pixel& p : goal_pixels) EXPECT_EQ(none.at(p.x, p.y), kWhite);
    for (const Pixel& p : plane_pixels) EXPECT_EQ(none.at(p.x, p.y), kWhite);

    // Colouring per surface switches the disks' colours.
    click("sg-layer-surfaces");
    const render::Image by_plane = screenshot();
    click("sg-colour-0");
    EXPECT_NE(non_white(by_plane), 0u);
    EXPECT_FALSE(screenshot() == by_plane);
}

// The first view is framed like the PNG: on the structure, not on a stray patch 30 m away.
TEST_F(ViewInBrowser, FirstViewIsFramedOnTheStructureLikeThePicture) {
    view::ViewerScene scene;
    scene.title = "framing";
    scene.units = "m";
    std::vector<render::Disk> disks;
    for (int i = 0; i <= 80; ++i)
        for (int j = 0; j <= 80; ++j)
            disks.push_back({Vec3d(0.0125 * i, 0.0125 * j, 1.0), Vec3d(0, 0, 1), 0.012,
                             render::Rgb{31, 119, 180}});
    for (int i = 0; i < 40; ++i)
        disks.push_back(
            {Vec3d(30.0 + 0.0125 * i, 0, 0), Vec3d(0, 0, 1), 0.012, render::Rgb{255, 127, 14}});
    scene.disks = disks;
    {
        std::ofstream page(dir_->path() / "framing.html", std::ios::binary);
        view::write_viewer_html(page, scene);
    }
    open("framing.html");
    // The plate's corners in the page, and in the PNG's iso view at the window's size.
    const std::vector<Vec3d> corners{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    auto span = [](const std::vector<Vec3d>& xy) {
        double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
        for (const Vec3d& p : xy)
            x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()),
            y1 = std::max(y1, p.y());
        return std::max(x1 - x0, y1 - y0);
    };
    std::vector<Vec3d> in_page, in_png;
    render::Scene picture;
    picture.disks = disks;
    render::RenderOptions options;
    options.width = kWidth;
    options.height = kHeight;
    const render::Camera camera = render::frame_scene(picture, options);
    for (const Vec3d& c : corners) {
        const json xy = browser_->evaluate(
            cat({"surfgrowView.project(", num(c.x()), ",", num(c.y()), ",", num(c.z()), ")"}));
        in_page.emplace_back(double(xy[0]), double(xy[1]), 0.0);
        in_png.push_back(camera.project(c));
    }
    const double page = span(in_page), png = span(in_png);
    std::printf("plate spans %.0f px in the page, %.0f px in the picture\n", page, png);
    // Perspective against orthographic, and the panel takes part of the window: comparable,
    // not equal. Framed on everything, the plate would span about 40 px.
    EXPECT_GT(page, 0.5 * png);
    EXPECT_LT(page, 1.5 * png);
    EXPECT_GT(page, 0.3 * kHeight);
}

// The harness itself: it must see what the viewer tests claim is absent.
TEST(HeadlessChromiumHarness, SeesConsoleErrorsExceptionsAndRequests) {
    const auto chromium = HeadlessChromium::find();
    if (!chromium) GTEST_SKIP() << "Chromium is not installed";
    test::TempDir dir;
    test::write_bytes(dir / "bad.html",
                      "<!DOCTYPE html><html><body><script>\n"
                      "console.log('fine'); console.error('deliberate');\n"
                      "fetch('http://surfgrow.invalid/x').catch(() => {});\n"
                      "setTimeout(() => { throw new Error('thrown'); }, 0);\n"
                      "</script></body></html>");
    HeadlessChromium browser(*chromium, dir.path(), 320, 240);
    browser.open("file://" + (dir / "bad.html").string());
    EXPECT_EQ(browser.evaluate("new Promise(r => setTimeout(() => r(6 * 7), 50))"), 42);
    std::string errors;
    for (const std::string& e : browser.errors()) errors += e + "\n";
    EXPECT_NE(errors.find("deliberate"), std::string::npos) << errors;
    EXPECT_NE(errors.find("thrown"), std::string::npos) << errors;
    EXPECT_EQ(errors.find("fine"), std::string::npos) << errors;
    bool fetched = false;
    for (const std::string& r : browser.requests()) fetched |= r == "http://surfgrow.invalid/x";
    EXPECT_TRUE(fetched);
    const render::Image shot = render::decode_png(browser.screenshot_png());
    EXPECT_EQ(shot.width(), 320);
    EXPECT_EQ(shot.height(), 240);
}

}  // namespace
}  // namespace surfgrow
