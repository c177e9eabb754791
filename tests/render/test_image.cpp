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
