// Cutting the image into tiles and listing, for each tile, the primitives that may touch it, so
// tiles can be rasterized one at a time (small buffers that stay in cache) and in parallel.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace surfgrow::render {

/// For each tile, the indices of the primitives whose box touches it, in increasing order.
struct Bins {
    std::vector<std::uint32_t> offset;  ///< tile t's items are items[offset[t], offset[t + 1])
    std::vector<std::uint32_t> items;
    [[nodiscard]] std::span<const std::uint32_t> of(int tile) const {
        const auto t = static_cast<std::size_t>(tile);
        return {items.data() + offset[t], items.data() + offset[t + 1]};
    }
};

/// Square tiles of `tile` pixels over a width x height image, row by row.
class TileGrid {
  public:
    TileGrid(int width, int height, int tile)
        : width_(width),
          height_(height),
          tile_(tile),
          cols_((width + tile - 1) / tile),
          rows_((height + tile - 1) / tile) {}

    [[nodiscard]] int count() const { return cols_ * rows_; }
    [[nodiscard]] int x0(int t) const { return (t % cols_) * tile_; }
    [[nodiscard]] int y0(int t) const { return (t / cols_) * tile_; }
    [[nodiscard]] int width(int t) const { return std::min(tile_, width_ - x0(t)); }
    [[nodiscard]] int height(int t) const { return std::min(tile_, height_ - y0(t)); }

    /// Bins primitives 0..n-1. `box(i, x0, y0, x1, y1)` gives primitive i's pixel box, or
    /// returns false to leave it out; boxes are widened by `pad` pixels.
    template <typename BoxFn>
    [[nodiscard]] Bins bin(std::size_t n, BoxFn&& box, double pad) const {
        Bins bins;
        bins.offset.assign(static_cast<std::size_t>(count()) + 1, 0);
        int c0 = 0, c1 = 0, r0 = 0, r1 = 0;
        auto range = [&](std::size_t i) {
            double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
            if (!box(i, x0, y0, x1, y1)) return false;
            if (!(x1 + pad >= 0 && y1 + pad >= 0 && x0 - pad < width_ && y0 - pad < height_))
                return false;  // off the image (or NaN)
            c0 = cell(x0 - pad, cols_), c1 = cell(x1 + pad, cols_);
            r0 = cell(y0 - pad, rows_), r1 = cell(y1 + pad, rows_);
            return true;
        };
        // Count per tile, then place: a counting sort that keeps each tile's items in order.
        for (std::size_t i = 0; i < n; ++i)
            if (range(i))
                for (int r = r0; r <= r1; ++r)
                    for (int c = c0; c <= c1; ++c) ++bins.offset[tile_index(r, c) + 1];
        for (std::size_t t = 1; t < bins.offset.size(); ++t) bins.offset[t] += bins.offset[t - 1];
        bins.items.resize(bins.offset.back());
        std::vector<std::uint32_t> next(bins.offset.begin(), bins.offset.end() - 1);
        for (std::size_t i = 0; i < n; ++i)
            if (range(i))
                for (int r = r0; r <= r1; ++r)
                    for (int c = c0; c <= c1; ++c)
                        bins.items[next[tile_index(r, c)]++] = static_cast<std::uint32_t>(i);
        return bins;
    }

  private:
    [[nodiscard]] int cell(double v, int cells) const {
        return static_cast<int>(std::clamp(std::floor(v / tile_), 0.0, cells - 1.0));
    }
    [[nodiscard]] std::size_t tile_index(int r, int c) const {
        return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) +
               static_cast<std::size_t>(c);
    }
    int width_, height_, tile_, cols_, rows_;
};

}  // namespace surfgrow::render
