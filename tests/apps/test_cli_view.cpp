// End-to-end tests of `surfgrow view`: the page the real binary writes, read back as data (the
// browser tests, in tests/view, open it in Chromium).
#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include <cmath>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/render/group_colors.hpp"
#include "surfgrow/render/scene_builder.hpp"
#include "surfgrow/view/assets.hpp"
#include "surfgrow/view/base64.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quoted;
using test::run_surfgrow;

// The text of <script ... id="ID">TEXT</script> in a page.
std::string block(const std::string& page, const std::string& id) {
    const std::string open = cat({"id=\"", id, "\">"});
    const auto start = page.find(open);
    if (start == std::string::npos) return {};
    const auto from = start + open.size();
    return page.substr(from, page.find("</script>", from) - from);
}

json meta_of(const std::string& page) {
    return json::parse(block(page, "sg-meta"));
}

template <class T>
std::vector<T> array_of(const std::string& page, const std::string& id) {
    const auto bytes = view::decode_base64(block(page, id));
    EXPECT_TRUE(bytes.has_value()) << id;
    if (!bytes) return {};
    std::vector<T> v(bytes->size() / sizeof(T));
    std::memcpy(v.data(), bytes->data(), v.size() * sizeof(T));
    return v;
}

// The page without the bundled three.js: what we wrote ourselves.
std::string without_library(std::string page) {
    for (std::string_view lib : {view::assets::three_js(), view::assets::orbit_controls_js()}) {
        const auto at = page.find(lib);
        EXPECT_NE(at, std::string::npos);
        if (at != std::string::npos) page.erase(at, lib.size());
    }
    return page;
}

class CliView : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir();
        box_ = new test::GrownBox(test::grow_box(dir_->path()));
    }
    static void TearDownTestSuite() {
        delete box_;
        delete dir_;
    }
    static std::string view(const fs::path& result, const std::string& args, const char* name) {
        const fs::path html = dir_->path() / name;
        const test::CliRun r =
            run_surfgrow(cat({"view ", quoted(result), " -o ", quoted(html), " ", args}));
        EXPECT_EQ(r.code, 0) << r.out;
        return test::read_bytes(html);
    }
    static std::size_t finite_points() {
        std::size_t n = 0;
        for (const Vec3f& p : box_->points.points) n += is_finite(p) ? 1 : 0;
        return n;
    }
    static inline test::TempDir* dir_ = nullptr;
    static inline test::GrownBox* box_ = nullptr;
};

TEST_F(CliView, WritesOneSelfContainedPage) {
    const std::string page = view(box_->out, "--cloud " + quoted(box_->cloud), "page.html");
    ASSERT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos);  // three.js is in the page
    EXPECT_NE(page.find("OrbitControls"), std::string::npos);
    // Nothing to fetch: no URL of ours, no external script, style, image or import.
    const std::string own = without_library(page);
    EXPECT_EQ(own.find("http://"), std::string::npos);
    EXPECT_EQ(own.find("https://"), std::string::npos);
    for (const char* ref : {"<script src", "<link", "<img", "<iframe", "@import", "url(", "fetch("})
        EXPECT_EQ(own.find(ref), std::string::npos) << ref;
    // The library's own URL strings are an XML namespace and comments, never fetched (the
    // browser test checks that no request leaves the page).
    const std::string lib(view::assets::three_js());
    const std::regex url("https?://[^\"' )\\n]*");
    for (auto it = std::sregex_iterator(lib.begin(), lib.end(), url); it != std::sregex_iterator();
         ++it) {
        const std::string u = it->str();
        EXPECT_TRUE(u == "http://www.w3.org/1999/xhtml" ||
                    u == "https://graphics.stanford.edu/papers/envmap/envmap.pdf")
            << u;
    }
}

TEST_F(CliView, PageDataMatchesTheResultAndTheCloud) {
    const std::string page = view(box_->out, "--cloud " + quoted(box_->cloud), "data.html");
    const json meta = meta_of(page);
    EXPECT_EQ(meta["format"], "surfgrow-view");
    EXPECT_EQ(meta["units"], "m");
    EXPECT_EQ(meta["back_faces"], "show");  // normals face the frame origin: a guess
    EXPECT_NE(meta["legend"].get<std::string>().find(" surfaces, "), std::string::npos);
    const json& layers = meta["layers"];
    EXPECT_TRUE(layers["planes"].is_null());
    EXPECT_TRUE(layers["path"].is_null());
    const Vec3d origin(meta["origin"][0], meta["origin"][1], meta["origin"][2]);

    // Disks: centre (relative to origin), unit normal, radius, as scene_from_surfaces makes them.
    const render::Scene scene = render::scene_from_surfaces(box_->result.surfaces);
    ASSERT_EQ(layers["surfaces"]["count"], scene.disks.size());
    const auto disks = array_of<float>(page, layers["surfaces"]["disks"]);
    const auto colors = array_of<std::uint8_t>(page, layers["surfaces"]["color"]);
    ASSERT_EQ(disks.size(), 7 * scene.disks.size());
    ASSERT_EQ(colors.size(), 3 * scene.disks.size());
    for (std::size_t i = 0; i < scene.disks.size(); ++i) {
        const render::Disk& d = scene.disks[i];
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(double(disks[7 * i + a]) + origin[a], d.center[a], 1e-6);
            EXPECT_NEAR(disks[7 * i + 3 + a], d.normal[a], 1e-6);
        }
        EXPECT_NEAR(disks[7 * i + 6], d.radius, 1e-7);
        EXPECT_EQ(colors[3 * i], d.color.r);
    }
    // Points: every finite point, in order, coloured by its surface as in the PNG.
    ASSERT_EQ(layers["cloud"]["count"], finite_points());
    const auto xyz = array_of<float>(page, layers["cloud"]["position"]);
    const auto rgb = array_of<std::uint8_t>(page, layers["cloud"]["color"]);
    ASSERT_EQ(xyz.size(), 3 * finite_points());
    render::Scene points = scene;  // with the disks, so each point knows its disk
    const auto labels = io::read_labels(box_->out / "labels.bin");
    render::add_points(points, box_->points, labels, box_->result.surfaces.size());
    // With each point, its surface's normal (Int8, x127), so it can go with its disk.
    const auto normals = array_of<std::int8_t>(page, layers["cloud"]["normal"]);
    ASSERT_EQ(normals.size(), 3 * finite_points());
    std::size_t registered = 0;
    for (std::size_t k = 0; k < points.points.size(); k += 97) {
        const render::ScenePoint& p = points.points[k];
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(double(xyz[3 * k + a]) + origin[a], double(p.position[a]), 1e-6);
        EXPECT_EQ(rgb[3 * k + 1], p.color.g);
        const Vec3d n =
            p.disk >= 0 ? scene.disks[static_cast<std::size_t>(p.disk)].normal : Vec3d::Zero();
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(normals[3 * k + a] / 127.0, n[a], 0.005);
        registered += p.disk >= 0;
    }
    EXPECT_GT(registered, 200u);
}

TEST_F(CliView, LargeCloudsAreSubsampledTheSameWayEveryTime) {
    const std::string args = "--max-points 1000 --cloud " + quoted(box_->cloud);
    const std::string a = view(box_->out, args, "sub-a.html");
    const std::string b = view(box_->out, args, "sub-b.html");
    EXPECT_EQ(a, b);
    const json meta = meta_of(a);
    EXPECT_EQ(meta["layers"]["cloud"]["count"], 1000);
    ASSERT_EQ(meta["notes"].size(), 1u);
    const std::string note = meta["notes"][0];
    EXPECT_NE(note.find("showing 1,000 of "), std::string::npos) << note;
    // Spread over the whole box, not the first thousand points of the file.
    const auto xyz = array_of<float>(a, meta["layers"]["cloud"]["position"]);
    float lo = INFINITY, hi = -INFINITY;
    for (std::size_t k = 2; k < xyz.size(); k += 3)
        lo = std::min(lo, xyz[k]), hi = std::max(hi, xyz[k]);
    EXPECT_GT(hi - lo, 0.29f);
    // --max-points 0: no cloud at all; without --cloud neither.
    EXPECT_FALSE(meta_of(view(box_->out, "--max-points 0 --cloud " + quoted(box_->cloud),
                              "none.html"))["layers"]
                     .contains("cloud"));
    EXPECT_FALSE(meta_of(view(box_->out, "", "nocloud.html"))["layers"].contains("cloud"));
}

TEST_F(CliView, OptionalLayersComeFromPlanesAndCoverageFiles) {
    test::TempDir tmp;
    test::GrownBox box = *box_;
    box.out = tmp / "out";
    fs::copy(box_->out, box.out);
    const std::size_t goals = test::write_layer_fixtures(box);
    const std::string page = view(box.out, "", "layers.html");
    const json layers = meta_of(page)["layers"];
    ASSERT_TRUE(layers["planes"].is_object());
    EXPECT_EQ(layers["planes"]["polygons"].size(), 6u);
    EXPECT_EQ(layers["planes"]["polygons"][0]["outline"], 4);
    EXPECT_EQ(array_of<float>(page, layers["planes"]["vertices"]).size(), 6u * 4u * 3u);
    ASSERT_TRUE(layers["path"].is_object());
    EXPECT_EQ(layers["path"]["count"], goals);
    // Colouring by plane: every disk of a plane gets the plane's colour, the PNG's
    // (group_colors: the box's faces meet, so the six differ), and so does its polygon.
    ASSERT_TRUE(layers["surfaces"]["plane_color"].is_string());
    const auto plane_rgb = array_of<std::uint8_t>(page, layers["surfaces"]["plane_color"]);
    const io::StoredPlanes planes = io::read_planes_json(box.out / "planes.json");
    const std::vector<render::Rgb> colors =
        render::group_colors(box.result.surfaces, planes.planes.plane_of_patch);
    std::set<std::tuple<int, int, int>> distinct;
    for (std::size_t id = 0; id < planes.planes.planes.size(); ++id) {
        ASSERT_FALSE(planes.planes.planes[id].patches.empty());
        const render::Rgb c = colors[planes.planes.planes[id].patches[0]];
        distinct.insert({c.r, c.g, c.b});
        for (const std::uint32_t s : planes.planes.planes[id].patches) {
            EXPECT_EQ(plane_rgb[3 * s], c.r);
            EXPECT_EQ(plane_rgb[3 * s + 1], c.g);
            EXPECT_EQ(plane_rgb[3 * s + 2], c.b);
        }
        const json& colour = layers["planes"]["polygons"][id]["color"];
        EXPECT_EQ(colour, json({c.r, c.g, c.b})) << colour;
    }
    EXPECT_EQ(distinct.size(), 6u);
}

TEST_F(CliView, SameBytesEveryRun) {
    const std::string args = "--cloud " + quoted(box_->cloud);
    EXPECT_EQ(view(box_->out, args, "same-a.html"), view(box_->out, args, "same-b.html"));
}

TEST_F(CliView, BadInputsGiveTheirCodeAndWriteNoPage) {
    test::TempDir tmp;
    fs::create_directories(tmp / "empty");
    fs::create_directories(tmp / "notresult");
    test::write_bytes(tmp / "notresult" / "surfaces.json", "[1, 2, 3]");
    test::write_bytes(tmp / "short.xyz", "0 0 0\n1 0 0\n0 1 0\n");
    auto with_layer = [&](const char* name, const char* file, const std::string& text) {
        fs::copy(box_->out, tmp / name);
        test::write_bytes(tmp / name / file, text);
        return quoted(tmp / name);
    };
    // A real planes.json (the box's faces), edited to break it.
    auto edited_planes = [&](const char* name, const std::function<void(json&)>& edit) {
        test::GrownBox box = *box_;
        box.out = tmp / name;
        fs::copy(box_->out, box.out);
        test::write_layer_fixtures(box);
        json j = json::parse(test::read_bytes(box.out / "planes.json"));
        edit(j);
        test::write_bytes(box.out / "planes.json", j.dump());
        return quoted(box.out);
    };
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
        {"not a result", quoted(tmp / "notresult"), ErrorCode::kMalformedInput, "surfaces.json"},
        {"negative max-points", out + " --max-points -1", ErrorCode::kInvalidParameter,
         "--max-points"},
        {"max-points not a number", out + " --max-points many", ErrorCode::kUsage, "max-points"},
        {"missing cloud", out + " --cloud " + quoted(tmp / "nope.ply"), ErrorCode::kCannotOpen,
         "nope.ply"},
        {"not the grown cloud", out + " --cloud " + quoted(tmp / "short.xyz"),
         ErrorCode::kMalformedInput, "is this the cloud that was grown"},
        {"planes.json not JSON", with_layer("p1", "planes.json", "{planes"),
         ErrorCode::kMalformedInput, "planes.json"},
        {"planes of another result",
         edited_planes(
             "p2",
             [](json& j) { j["summary"]["patches"] = j["summary"]["patches"].get<int>() + 5; }),
         ErrorCode::kMalformedInput, "run `surfgrow planes` again"},
        {"plane of two vertices",
         edited_planes("p3",
                       [](json& j) {
                           j["planes"][0]["polygons"][0]["outer"] = json::array({{0, 0}, {1, 0}});
                       }),
         ErrorCode::kMalformedInput, "a ring needs at least 3"},
        {"coverage in other units",
         with_layer("c1", "coverage.json", R"({"units": "mm", "goals": []})"),
         ErrorCode::kMalformedInput, "coverage.json"},
        {"coverage goal without position",
         with_layer("c2", "coverage.json", R"({"goals": [{"pos": [0, 0, 0]}]})"),
         ErrorCode::kMalformedInput, "coverage.json"},
    };
    for (const Case& c : cases) {
        const fs::path html = tmp / cat({"out-", std::to_string(&c - cases.data()), ".html"});
        const test::CliRun r = run_surfgrow(cat({"view ", c.args, " -o ", quoted(html)}));
        EXPECT_EQ(r.code, static_cast<int>(c.code)) << c.name << ": " << r.out;
        EXPECT_NE(r.out.find(c.message), std::string::npos) << c.name << ": " << r.out;
        EXPECT_FALSE(fs::exists(html)) << c.name;
    }
    EXPECT_EQ(run_surfgrow(cat({"view ", out})).code, static_cast<int>(ErrorCode::kUsage));
}

}  // namespace
}  // namespace surfgrow
