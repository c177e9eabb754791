// The software rasterizer: a supersampled colour + depth buffer for one tile of the image, into
// which disks, lines and dots are drawn with a depth test, then averaged down (antialiasing).
#pragma once

#include <cstdint>
#include <vector>

#include "surfgrow/render/color.hpp"
#include "surfgrow/render/image.hpp"

namespace surfgrow::render {

/// A filled ellipse with a linear depth: a disk as the camera sees it. All in image pixels.
struct ScreenEllipse {
    double cx = 0.0, cy = 0.0;  ///< centre
    double ux = 1.0, uy = 0.0;  ///< unit direction of the major axis
    double a = 0.0;             ///< semi-major axis
    double b = 0.0;             ///< semi-minor axis (along (-uy, ux))
    double depth = 0.0;         ///< depth at the centre
    double depth_b = 0.0;       ///< depth change from the centre to the end of (-uy, ux) * b
    Rgb fill;
    Rgb rim;               ///< colour of the outer ring
    double rim_start = 2;  ///< ring where (alpha^2 + beta^2) > rim_start (>= 1: no ring)

    /// Half the width and height of its bounding box.
    [[nodiscard]] double half_width() const;
    [[nodiscard]] double half_height() const;
};

/// Colour and depth per sample, `samples` x `samples` per pixel, for a window of the image
/// (a tile) plus an apron of samples around it, so that work on a tile can look a little past
/// its edges. Smaller depth wins; on equal depth the first drawn stays, so drawing in scene
/// order gives the same picture whatever the tiling. Coordinates are image pixels.
class Raster {
  public:
    /// `samples` per pixel along each axis: 1 to 4.
    Raster(int samples, int apron);

    /// Makes the window pixels [x0, x0 + width) x [y0, y0 + height), all background.
    void reset(int x0, int y0, int width, int height, Rgb background);

    [[nodiscard]] int samples() const { return ss_; }

    void fill_ellipse(const ScreenEllipse& e);
    /// A round dot of `radius` pixels (never smaller than one sample) at (x, y).
    void fill_dot(double x, double y, double depth, double radius, Rgb color);
    /// A line of `half_width` pixels from (x0, y0, d0) to (x1, y1, d1), depth interpolated.
    void draw_segment(double x0, double y0, double d0, double x1, double y1, double d1,
                      double half_width, Rgb color);

    /// Mixes `color` (weight `strength`) into samples within about a pixel of a depth step
    /// larger than `step` (silhouettes, an edge passing in front of a face): the lines a
    /// draughtsman draws. Looks `apron` samples (at least one) to each side.
    void outline(double step, Rgb color, double strength);

    /// While on, only one sample in three is drawn (a fixed diagonal pattern in image sample
    /// coordinates): screen-door transparency, seen through once samples are averaged.
    void set_ghost(bool on) { ghost_ = on; }

    /// Writes the average of each window pixel's samples into `image`.
    void resolve_into(Image& image) const;

  private:
    // First and last buffer column (row) whose sample centre lies in [lo, hi] (image samples).
    [[nodiscard]] bool span_x(double lo, double hi, int& first, int& last) const;
    [[nodiscard]] bool span_y(double lo, double hi, int& first, int& last) const;
    [[nodiscard]] std::size_t index(int bx, int by) const {
        return static_cast<std::size_t>(by) * static_cast<std::size_t>(bw_) +
               static_cast<std::size_t>(bx);
    }
    // The depth test: sample i takes `color` where `depth` is nearer than what it holds.
    void put(std::size_t i, float depth, std::uint32_t color) {
        if (depth < depth_[i]) {
            depth_[i] = depth;
            color_[i] = color;
        }
    }
    void plot(std::size_t i, int bx, int by, float depth, std::uint32_t color) {
        if (ghost_ && (bx + by + ghost_phase_) % 3 != 0) return;
        put(i, depth, color);
    }

    int ss_, apron_;
    int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;  // the window, pixels
    int gx0_ = 0, gy0_ = 0;                         // image sample of buffer (0, 0)
    int bw_ = 0, bh_ = 0;                           // buffer size, samples
    int ghost_phase_ = 0;                           // (gx0 + gy0) mod 3
    bool ghost_ = false;
    std::vector<std::uint32_t> color_;  // 0x00RRGGBB
    std::vector<float> depth_;
    std::vector<float> scratch_;      // depth copy for outline()
    std::vector<std::uint8_t> edge_;  // outline(): one row's edge flags
};

}  // namespace surfgrow::render
