// Image, colours and PNG encoding.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <set>
#include <sstream>
#include <tuple>

#include "surfgrow/core/error.hpp"
#include "surfgrow/render/color.hpp"
#include "surfgrow/render/image.hpp"
#include "surfgrow/render/png.hpp"

using namespace surfgrow;
using namespace surfgrow::render;

namespace {

ErrorCode code_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.code();
    }
    return ErrorCode::kInternal;
}

Image noise_image(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    Image img(w, h);
    for (auto& b : img.bytes()) b = static_cast<std::uint8_t>(rng());
    return img;
}

}  // namespace

TEST(Image, FillsAndAddressesPixels) {
    Image img(4, 3, {1, 2, 3});
    EXPECT_EQ(img.width(), 4);
    EXPECT_EQ(img.height(), 3);
    EXPECT_EQ(img.bytes().size(), 36u);
    EXPECT_EQ(img.count({1, 2, 3}), 12u);
    img.set(3, 2, {9, 8, 7});
    EXPECT_EQ(img.at(3, 2), (Rgb{9, 8, 7}));
    EXPECT_EQ(img.bytes()[33], 9);  // last pixel, row-major RGB
    EXPECT_TRUE(img.contains(0, 0));
    EXPECT_FALSE(img.contains(4, 0));
    EXPECT_FALSE(img.contains(0, -1));
}

TEST(Image, BlendMixesByOpacity) {
    Image img(1, 1, {0, 0, 0});
    img.blend(0, 0, {200, 100, 50}, 0.5);
    EXPECT_EQ(img.at(0, 0), (Rgb{100, 50, 25}));
}

TEST(Image, NegativeSizeIsAnInvalidParameter) {
    EXPECT_EQ(code_of([] { Image(-1, 5); }), ErrorCode::kInvalidParameter);
}

TEST(Color, IdColorsAreDeterministicAndDistinct) {
    EXPECT_EQ(id_color(17), id_color(17));
    EXPECT_EQ(id_color(-1), kUnassignedGrey);
    std::set<std::tuple<int, int, int>> seen;
    for (int i = 0; i < 1000; ++i) {
        const Rgb a = id_color(i), b = id_color(i + 1);
        seen.insert({a.r, a.g, a.b});
        // Neighbouring ids must not look alike.
        const int diff = std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
        EXPECT_GT(diff, 40) << "ids " << i << " and " << i + 1;
    }
    EXPECT_GT(seen.size(), 950u);
}

TEST(Color, HsvPrimaries) {
    EXPECT_EQ(hsv_to_rgb(0.0, 1.0, 1.0), (Rgb{255, 0, 0}));
    EXPECT_EQ(hsv_to_rgb(1.0 / 3, 1.0, 1.0), (Rgb{0, 255, 0}));
    EXPECT_EQ(hsv_to_rgb(2.0 / 3, 1.0, 1.0), (Rgb{0, 0, 255}));
    EXPECT_EQ(hsv_to_rgb(0.5, 0.0, 0.5), (Rgb{128, 128, 128}));
    EXPECT_EQ(scaled({100, 200, 250}, 2.0), (Rgb{200, 255, 255}));
    EXPECT_EQ(mix({0, 0, 0}, {255, 255, 255}, 1.0), (Rgb{255, 255, 255}));
}

TEST(Png, RoundTripsSizeAndPixels) {
    const Image img = noise_image(37, 23, 5);
    std::stringstream ss;
    write_png(img, ss);
    const std::string bytes = ss.str();
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(1, 3), "PNG");
    ss.seekg(0);
    const Image back = read_png(ss);
    EXPECT_EQ(back.width(), 37);
    EXPECT_EQ(back.height(), 23);
    EXPECT_TRUE(back == img);
}

TEST(Png, GarbageIsMalformedInput) {
    EXPECT_EQ(code_of([] { (void)decode_png("not a png at all"); }), ErrorCode::kMalformedInput);
    std::string truncated = encode_png(noise_image(20, 20, 1));
    truncated.resize(truncated.size() / 2);
    EXPECT_EQ(code_of([&] { (void)decode_png(truncated); }), ErrorCode::kMalformedInput);
}

TEST(Png, EmptyImageIsAnInvalidParameter) {
    EXPECT_EQ(code_of([] { (void)encode_png(Image()); }), ErrorCode::kInvalidParameter);
}

TEST(Png, FailingStreamIsCannotWrite) {
    std::stringstream ss;
    ss.setstate(std::ios::badbit);
    EXPECT_EQ(code_of([&] { write_png(noise_image(4, 4, 2), ss); }), ErrorCode::kCannotWrite);
}

// The rows are deflated in blocks of 64, each primed with the rows before it: pictures of one
// block, of a block and a row, of many blocks (rows longer and shorter than deflate's 32 KB
// window), flat or noisy, decode to the same pixels, in the same bytes for any thread count.
TEST(Png, BlocksOfRowsRoundTripTheSameForAnyThreads) {
    struct Case {
        int w, h;
        bool noise;
    };
    for (const Case c : {Case{5, 1, true}, Case{64, 64, true}, Case{300, 65, false},
                         Case{1, 1000, true}, Case{12000, 130, true}, Case{640, 257, false}}) {
        Image img = c.noise ? noise_image(c.w, c.h, 9) : Image(c.w, c.h, {20, 40, 60});
        if (!c.noise)  // flat bands: what deflate's back-references across blocks see
            for (int y = 0; y < c.h; ++y)
                for (int x = 0; x < c.w; x += 7) img.set(x, y, {uint8_t(y), uint8_t(x), 9});
        const std::string one = encode_png(img, 1);
        EXPECT_TRUE(decode_png(one) == img) << c.w << " x " << c.h;
        EXPECT_EQ(encode_png(img, 2), one) << c.w << " x " << c.h;
        EXPECT_EQ(encode_png(img, 0), one) << c.w << " x " << c.h;
    }
}

// Priming each block with the rows before it keeps what deflate finds across block edges: a
// picture whose rows repeat every 50 rows (15 KB, within deflate's window) compresses to about
// one period, as one stream would; blocks without the priming would each pay for a period again.
TEST(Png, BlocksKeepTheRepeatsAcrossTheirEdges) {
    const Image stripe = noise_image(100, 50, 3);
    Image img(100, 700);
    for (int y = 0; y < 700; ++y)
        for (int x = 0; x < 100; ++x) img.set(x, y, stripe.at(x, y % 50));
    const std::string bytes = encode_png(img, 2);
    EXPECT_TRUE(decode_png(bytes) == img);
    // One period of noise is 15 KB; 11 blocks that each paid for it would be over 160 KB.
    EXPECT_LT(bytes.size(), 30000u);
}
