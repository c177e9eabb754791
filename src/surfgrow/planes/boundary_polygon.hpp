// Boundary polygons of a raster: marching squares, hole nesting, Douglas-Peucker simplification.
#pragma once

#include <vector>

#include "surfgrow/planes/plane_raster.hpp"
#include "surfgrow/planes/polygon2d.hpp"

namespace surfgrow {

/// Polygons bounding the occupied cells of `raster`, in the raster's 2D coordinates.
///
/// Marching squares over the cell centres puts each contour vertex halfway between an occupied
/// and an empty centre, so a polygon encloses its cells' centres with half a cell to spare.
/// Diagonal neighbours count as connected (8-connected cells; the empty side 4-connected), so
/// contours never cross or touch. Outer rings come out counter-clockwise, holes clockwise; each
/// hole goes with the smallest outer ring containing it. Holes of less than `min_hole_area` are
/// dropped. Each ring is then simplified by simplify_ring(tolerance). Polygons are ordered by
/// their outer ring's lowest-then-leftmost vertex; deterministic.
[[nodiscard]] std::vector<PolygonWithHoles> trace_boundaries(const PlaneRaster& raster,
                                                             double simplify_tolerance,
                                                             double min_hole_area = 0.0);

/// Douglas-Peucker simplification of a closed ring: every dropped vertex lies within `tolerance`
/// of the simplified ring. The ring is split at its lowest-then-leftmost vertex and the vertex
/// farthest from it, which are always kept; at least 3 vertices are kept when the ring has 3.
/// Orientation is preserved. tolerance <= 0 only drops repeated and collinear vertices.
[[nodiscard]] Ring simplify_ring(const Ring& ring, double tolerance);

}  // namespace surfgrow
