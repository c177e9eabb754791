// A binary raster over a plane's 2D coordinates: where a region's points lie, gaps closed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/planes/polygon2d.hpp"

namespace surfgrow {

/// Occupancy of square cells over a plane; cell (x, y) has its centre at origin + cell * (x, y).
/// Row-major: cells[y * width + x], 1 where occupied.
struct PlaneRaster {
    Vec2d origin = Vec2d::Zero();
    double cell = 1.0;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> cells;

    [[nodiscard]] bool at(int x, int y) const {
        return cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)] != 0;
    }
    [[nodiscard]] Vec2d centre(double x, double y) const { return origin + cell * Vec2d(x, y); }
    [[nodiscard]] std::size_t occupied() const;
};

/// Largest raster rasterise_points() builds; a larger extent gets coarser cells.
inline constexpr std::size_t kMaxRasterCells = std::size_t{1} << 24;

/// Marks the cell of every point, then closes gaps of up to about 2 * closing_radius by a
/// morphological closing with a disc (dilate, then erode, both exact Euclidean by distance
/// transform). The raster has an empty border of at least one cell beyond the dilation, so every
/// contour is closed. `cell` grows if the points' extent would need more than kMaxRasterCells
/// cells (the raster's `cell` says what was used). Requires cell > 0, closing_radius >= 0 and at
/// least one point; every point must be finite.
[[nodiscard]] PlaneRaster rasterise_points(std::span<const Vec2d> points, double cell,
                                           double closing_radius);

/// rasterise_points' first half: the cells of the points marked, with the empty border the
/// closing needs (close_gaps does it).
[[nodiscard]] PlaneRaster mark_points(std::span<const Vec2d> points, double cell,
                                      double closing_radius);

/// rasterise_points' second half: the morphological closing of the marked cells by a disc of
/// `closing_radius` (none at 0), in place. The raster needs the border mark_points leaves.
void close_gaps(PlaneRaster& raster, double closing_radius);

/// Squared Euclidean distance, in cells, from every cell to the nearest cell where
/// feature[i] != 0 (Felzenszwalb and Huttenlocher's linear-time transform). Cells with no
/// feature anywhere get a large finite value.
void squared_distance_transform(std::span<const std::uint8_t> feature, int width, int height,
                                std::vector<double>& out);

/// The cells, of side `cell` and centred on a lattice through `phase`, whose centres lie inside
/// the polygons (even-odd over all rings, so holes stay empty), by scanline fill over an active
/// edge list: cost linear in the cells, the edges and the crossings. The raster spans the polygons'
/// bounding box; `cell` grows if that would need more than kMaxRasterCells cells. Empty (0 x 0)
/// when there are no polygons.
[[nodiscard]] PlaneRaster rasterise_polygons(std::span<const PolygonWithHoles> polygons,
                                             double cell, const Vec2d& phase = Vec2d::Zero());

}  // namespace surfgrow
