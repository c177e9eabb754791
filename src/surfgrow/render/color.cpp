#include "surfgrow/render/color.hpp"

#include <algorithm>
#include <cmath>

namespace surfgrow::render {

namespace {

std::uint8_t to_byte(double v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0)));
}

}  // namespace

Rgb hsv_to_rgb(double hue, double saturation, double value) {
    const double h = (hue - std::floor(hue)) * 6.0;
    const double s = std::clamp(saturation, 0.0, 1.0);
    const double v = std::clamp(value, 0.0, 1.0);
    const int sector = std::min(static_cast<int>(h), 5);
    const double f = h - sector;
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (sector) {
        case 0:
            r = v, g = t, b = p;
            break;
        case 1:
            r = q, g = v, b = p;
            break;
        case 2:
            r = p, g = v, b = t;
            break;
        case 3:
            r = p, g = q, b = v;
            break;
        case 4:
            r = t, g = p, b = v;
            break;
        default:
            r = v, g = p, b = q;
            break;
    }
    return {to_byte(255 * r), to_byte(255 * g), to_byte(255 * b)};
}

Rgb id_color(std::int64_t id) {
    if (id < 0) return kUnassignedGrey;
    constexpr double kGolden = 0.618033988749895;
    const auto k = static_cast<std::uint64_t>(id);
    const double hue = 0.58 + kGolden * static_cast<double>(k % 100003);
    // Period 3 and 5 cycles in saturation and value: two ids with near hues (k and k + 21, ...)
    // then mostly differ in one of the other two.
    // Muted: the shading, not the colour noise, has to carry the shape.
    static constexpr double kSat[3] = {0.34, 0.25, 0.43};
    static constexpr double kVal[5] = {0.97, 0.90, 1.00, 0.94, 0.87};
    return hsv_to_rgb(hue, kSat[k % 3], kVal[k % 5]);
}

Rgb mix(Rgb a, Rgb b, double t) {
    t = std::clamp(t, 0.0, 1.0);
    auto m = [t](std::uint8_t x, std::uint8_t y) { return to_byte(x + (y - x) * t); };
    return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
}

Rgb scaled(Rgb c, double factor) {
    return {to_byte(c.r * factor), to_byte(c.g * factor), to_byte(c.b * factor)};
}

double luminance(Rgb c) {
    return (0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b) / 255.0;
}

}  // namespace surfgrow::render
