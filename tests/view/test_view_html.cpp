// Tests of surfgrow_view without a browser: base64, the subsample, the page's layout and escaping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "surfgrow/view/assets.hpp"
#include "surfgrow/view/base64.hpp"
#include "surfgrow/view/subsample.hpp"
#include "surfgrow/view/viewer_html.hpp"

namespace surfgrow::view {
namespace {

std::string encode(std::string_view bytes) {
    std::string out;
    append_base64(out, bytes.data(), bytes.size());
    return out;
}

TEST(Base64, Rfc4648Vectors) {
    const std::pair<const char*, const char*> vectors[] = {
        {"", ""},
        {"f", "Zg=="},
        {"fo", "Zm8="},
        {"foo", "Zm9v"},
        {"foob", "Zm9vYg=="},
        {"fooba", "Zm9vYmE="},
        {"foobar", "Zm9vYmFy"},
    };
    for (const auto& [plain, coded] : vectors) {
        EXPECT_EQ(encode(plain), coded);
        EXPECT_EQ(decode_base64(coded), std::string(plain));
    }
}

TEST(Base64, RoundTripsEveryByte) {
    std::string bytes;
    for (int i = 0; i < 256 * 3 + 1; ++i) bytes.push_back(static_cast<char>(i * 7 % 256));
    EXPECT_EQ(decode_base64(encode(bytes)), bytes);
}

TEST(Base64, RefusesWhatIsNotBase64) {
    for (const char* bad : {"Zg=", "Z===", "Zm9v!", "Zg==Zg==", "=Zg=", "Zm 9"})
        EXPECT_FALSE(decode_base64(bad).has_value()) << bad;
}

TEST(ChoosePoints, KeepsEveryFinitePointUpToTheLimit) {
    PointCloud cloud;
    for (int i = 0; i < 100; ++i) cloud.points.emplace_back(float(i), 0.f, 0.f);
    cloud.points[10] = Vec3f::Constant(NAN);
    const auto keep = choose_points(cloud, 1000);
    ASSERT_EQ(keep.size(), 99u);
    EXPECT_EQ(keep[9], 9u);
    EXPECT_EQ(keep[10], 11u);
}

TEST(ChoosePoints, ExactCountSortedDeterministicAndSpread) {
    PointCloud cloud;
    for (int i = 0; i < 100000; ++i) cloud.points.emplace_back(float(i), 0.f, 0.f);
    const auto a = choose_points(cloud, 10000);
    ASSERT_EQ(a.size(), 10000u);
    EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
    EXPECT_EQ(std::adjacent_find(a.begin(), a.end()), a.end());
    EXPECT_EQ(choose_points(cloud, 10000), a);
    // About a tenth of every tenth of the cloud: no clustering at one end, no stripes.
    for (int part = 0; part < 10; ++part) {
        const auto n = std::count_if(a.begin(), a.end(), [&](std::uint32_t i) {
            return i / 10000 == static_cast<std::uint32_t>(part);
        });
        EXPECT_NEAR(double(n), 1000.0, 120.0) << part;
    }
    std::size_t every_tenth = 0;
    for (std::uint32_t i : a) every_tenth += i % 10 == 0;
    EXPECT_NEAR(double(every_tenth), 1000.0, 120.0);
    EXPECT_TRUE(choose_points(cloud, 0).empty());
}

TEST(Assets, TheTemplateHasEachMarkerOnce) {
    const std::string page(assets::page_template());
    for (const char* marker :
         {"@TITLE@", "@CSS@", "@META@", "@DATA@", "@THREE@", "@ORBIT@", "@VIEWER@"}) {
        const auto first = page.find(marker);
        ASSERT_NE(first, std::string::npos) << marker;
        EXPECT_EQ(page.find(marker, first + 1), std::string::npos) << marker;
    }
    EXPECT_NE(assets::three_js().find("REVISION=\"111\""), std::string::npos);
    EXPECT_NE(assets::orbit_controls_js().find("exports.OrbitControls"), std::string::npos);
    EXPECT_NE(assets::page_js().find("surfgrowView"), std::string::npos);
}

ViewerScene small_scene() {
    // Strings moved in, not assigned from literals: GCC 12 at -O3 reports a false -Wrestrict
    // on assigning short literals (its bug 105329), depending on what else got inlined.
    ViewerScene s;
    s.title = std::string("box");
    s.units = std::string("m");
    s.legend = std::string("10 points -> 2 surfaces, 100.0% registered");
    s.offset = Vec3d(1000, 2000, 0);
    s.disks = {{{0, 0, 0}, {0, 0, 1}, 0.1, {200, 10, 10}},
               {{1, 0, 0}, {1, 0, 0}, 0.1, {10, 200, 10}},
               {{5, 5, 5}, {0, 0, 1}, 0.0, {1, 1, 1}}};  // radius 0: left out
    s.points = {{{0.f, 0.f, 0.f}, {9, 9, 9}, 0}, {{NAN, 0.f, 0.f}, {9, 9, 9}, -1}};
    return s;
}

std::string script_block(const std::string& page, const std::string& id) {
    const std::string open = "id=\"" + id + "\">";
    const auto from = page.find(open) + open.size();
    return page.substr(from, page.find("</script>", from) - from);
}

TEST(ViewerHtml, MetaDescribesTheLayersAndTheFrame) {
    const std::string page = viewer_html(small_scene());
    const auto meta = nlohmann::json::parse(script_block(page, "sg-meta"));
    EXPECT_EQ(meta["layers"]["surfaces"]["count"], 2);
    EXPECT_EQ(meta["layers"]["cloud"]["count"], 1);
    EXPECT_TRUE(meta["layers"]["planes"].is_null());
    EXPECT_TRUE(meta["layers"]["path"].is_null());
    EXPECT_TRUE(meta["layers"]["surfaces"]["plane_color"].is_null());
    // Framed on the disks (x from -0.1 to 1.1): the origin is their box's centre, in file
    // coordinates, and positions are stored relative to it.
    EXPECT_DOUBLE_EQ(meta["origin"][0], 1000.5);
    EXPECT_DOUBLE_EQ(meta["origin"][1], 2000.0);
    const auto disks = decode_base64(script_block(page, "sg-disks"));
    ASSERT_TRUE(disks);
    ASSERT_EQ(disks->size(), 2u * 7u * sizeof(float));
    float first[7];
    std::memcpy(first, disks->data(), sizeof first);
    EXPECT_FLOAT_EQ(first[0], -0.5f);
    EXPECT_FLOAT_EQ(first[5], 1.0f);
    EXPECT_FLOAT_EQ(first[6], 0.1f);
    // The one finite point lies on disk 0: its normal travels with it, x127.
    EXPECT_EQ(decode_base64(script_block(page, "sg-cloud-normal")), std::string("\0\0\x7f", 3));
}

TEST(ViewerHtml, OptionalLayersWhenGiven) {
    ViewerScene s = small_scene();
    s.planes.emplace();
    s.planes->push_back({7, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {}, {1, 2, 3}});
    s.path = std::vector<Vec3d>{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}};
    s.disk_plane_colors = {{5, 5, 5}, {6, 6, 6}, {7, 7, 7}};
    const std::string page = viewer_html(s);
    const auto meta = nlohmann::json::parse(script_block(page, "sg-meta"));
    EXPECT_EQ(meta["layers"]["planes"]["polygons"][0]["plane"], 7);
    EXPECT_EQ(meta["layers"]["planes"]["polygons"][0]["outline"], 4);
    EXPECT_EQ(meta["layers"]["path"]["count"], 3);
    const auto plane_rgb = decode_base64(script_block(page, "sg-disk-plane-rgb"));
    ASSERT_TRUE(plane_rgb);
    EXPECT_EQ(*plane_rgb, std::string("\5\5\5\6\6\6", 6));  // the disk of radius 0 is left out
}

TEST(ViewerHtml, TextCannotBreakOutOfThePage) {
    ViewerScene s = small_scene();
    s.title = "a</title><script>alert(1)</script>";
    s.legend = "</script><script>alert(2)</script>";
    s.notes = {"<!-- x"};
    const std::string page = viewer_html(s);
    EXPECT_EQ(page.find("alert(1)</script>"), std::string::npos);
    EXPECT_EQ(page.find("<script>alert(2)"), std::string::npos);
    EXPECT_NE(page.find("a&lt;/title&gt;"), std::string::npos);
    const auto meta = nlohmann::json::parse(script_block(page, "sg-meta"));
    EXPECT_EQ(meta["legend"], s.legend);  // intact once parsed
    EXPECT_EQ(meta["notes"][0], "<!-- x");
}

TEST(ViewerHtml, DeterministicAndSelfContained) {
    const std::string a = viewer_html(small_scene());
    EXPECT_EQ(viewer_html(small_scene()), a);
    EXPECT_EQ(a.find("<script src"), std::string::npos);
    EXPECT_EQ(a.find("<link"), std::string::npos);
}

TEST(ViewerHtml, AnEmptySceneIsStillAPage) {
    const std::string page = viewer_html(ViewerScene{});
    const auto meta = nlohmann::json::parse(script_block(page, "sg-meta"));
    EXPECT_FALSE(meta["layers"].contains("surfaces"));
    EXPECT_FALSE(meta["layers"].contains("cloud"));
    EXPECT_NE(page.find("<title>surfgrow view</title>"), std::string::npos);
}

}  // namespace
}  // namespace surfgrow::view
