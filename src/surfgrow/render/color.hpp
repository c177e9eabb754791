// Colours of the picture: 8-bit RGB, distinct colours per id, and simple colour arithmetic.
#pragma once

#include <cstdint>

namespace surfgrow::render {

/// An opaque 8-bit sRGB colour.
struct Rgb {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;
    friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// The greys the renderer uses for things without a colour of their own.
inline constexpr Rgb kUnassignedGrey{150, 150, 150};  ///< unregistered points, group -1
inline constexpr Rgb kNormalRed{200, 40, 40};         ///< normals, as in the paper's Fig. 6f

/// A colour for an id (surface index, bound-plane id, label): deterministic, and ids next to each
/// other get far-apart hues (golden-ratio hue stepping), so neighbouring surfaces stay distinct.
/// Saturation and value cycle slowly too, which separates ids whose hues come out close. Negative
/// ids give kUnassignedGrey.
[[nodiscard]] Rgb id_color(std::int64_t id);

/// HSV (each in [0, 1]; hue wraps) to RGB.
[[nodiscard]] Rgb hsv_to_rgb(double hue, double saturation, double value);

/// a + (b - a) * t, per channel, t in [0, 1].
[[nodiscard]] Rgb mix(Rgb a, Rgb b, double t);

/// The colour times `factor` per channel (clamped to 255): shading.
[[nodiscard]] Rgb scaled(Rgb c, double factor);

/// Relative luminance in [0, 1] (Rec. 709 weights on the 8-bit values, no gamma).
[[nodiscard]] double luminance(Rgb c);

}  // namespace surfgrow::render
