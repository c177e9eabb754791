// An 8-bit RGB raster image, the renderer's output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "surfgrow/render/color.hpp"

namespace surfgrow::render {

/// width x height RGB pixels, row-major, top row first, 3 bytes per pixel (the PNG layout).
class Image {
  public:
    Image() = default;
    /// Throws Error(kInvalidParameter) for a negative size; 0 x 0 is an empty image.
    Image(int width, int height, Rgb fill = {});

    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }
    [[nodiscard]] bool empty() const { return width_ == 0 || height_ == 0; }
    [[nodiscard]] bool contains(int x, int y) const {
        return x >= 0 && y >= 0 && x < width_ && y < height_;
    }

    /// The pixel at column x, row y (both in range).
    [[nodiscard]] Rgb at(int x, int y) const {
        const std::uint8_t* p = &bytes_[offset(x, y)];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, Rgb c) {
        std::uint8_t* p = &bytes_[offset(x, y)];
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
    }
    /// Draws `c` over the pixel with opacity `alpha` in [0, 1] (antialiased overlays).
    void blend(int x, int y, Rgb c, double alpha) { set(x, y, mix(at(x, y), c, alpha)); }

    [[nodiscard]] const std::vector<std::uint8_t>& bytes() const { return bytes_; }
    [[nodiscard]] std::vector<std::uint8_t>& bytes() { return bytes_; }
    [[nodiscard]] std::size_t row_stride() const { return 3 * static_cast<std::size_t>(width_); }

    /// Pixels equal to `c` (tests and checks).
    [[nodiscard]] std::size_t count(Rgb c) const;

    friend bool operator==(const Image&, const Image&) = default;

  private:
    [[nodiscard]] std::size_t offset(int x, int y) const {
        return 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                    static_cast<std::size_t>(x));
    }
    int width_ = 0;
    int height_ = 0;
    std::vector<std::uint8_t> bytes_;
};

}  // namespace surfgrow::render
