// Boundary polygons from rasters, their simplification, and triangulation with holes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "surfgrow/core/error.hpp"
#include "surfgrow/planes/boundary_polygon.hpp"
#include "surfgrow/planes/plane_raster.hpp"
#include "surfgrow/planes/polygon_triangulation.hpp"

namespace surfgrow {
namespace {

// Points on a grid of `step` over [x0, x1] x [y0, y1], except where `skip` says.
template <class Skip>
std::vector<Vec2d> grid(double x0, double x1, double y0, double y1, double step, Skip skip) {
    std::vector<Vec2d> pts;
    for (double x = x0; x <= x1 + 1e-9; x += step)
        for (double y = y0; y <= y1 + 1e-9; y += step)
            if (!skip(x, y)) pts.emplace_back(x, y);
    return pts;
}

double triangles_area(const Triangulation& t) {
    double a = 0;
    for (const auto& tri : t.triangles)
        a += 0.5 * orient2d(t.vertices[tri[0]], t.vertices[tri[1]], t.vertices[tri[2]]);
    return a;
}

TEST(PlaneRaster, DistanceTransformIsExact) {
    // One feature cell in a 7 x 5 raster: squared distances are dx^2 + dy^2.
    std::vector<std::uint8_t> f(35, 0);
    f[2 * 7 + 3] = 1;
    std::vector<double> d;
    squared_distance_transform(f, 7, 5, d);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            EXPECT_DOUBLE_EQ(d[std::size_t(y * 7 + x)],
                             double((x - 3) * (x - 3) + (y - 2) * (y - 2)));
}

TEST(PlaneRaster, ClosingFillsGapsBetweenPointsButNotWideHoles) {
    // Points 5 mm apart with a 40 mm square hole; cells of 3 mm, closing 5 mm.
    const auto pts = grid(0, 0.2, 0, 0.2, 0.005, [](double x, double y) {
        return x > 0.08 && x < 0.12 && y > 0.08 && y < 0.12;
    });
    const PlaneRaster r = rasterise_points(pts, 0.003, 0.005);
    const auto polys = trace_boundaries(r, 0.0);
    ASSERT_EQ(polys.size(), 1u);
    ASSERT_EQ(polys[0].holes.size(), 1u);
    // Without closing, every empty cell between points is a hole.
    const auto open = trace_boundaries(rasterise_points(pts, 0.003, 0.0), 0.0);
    std::size_t holes = 0;
    for (const auto& p : open) holes += p.holes.size();
    EXPECT_GT(holes + open.size(), 100u);
}

TEST(PlaneRaster, RefusesBadArguments) {
    const std::vector<Vec2d> pts = {{0, 0}};
    EXPECT_THROW((void)rasterise_points(pts, 0.0, 0.0), Error);
    EXPECT_THROW((void)rasterise_points(pts, 0.01, -1.0), Error);
    EXPECT_THROW((void)rasterise_points({}, 0.01, 0.0), Error);
}

TEST(PlaneRaster, HugeExtentsGetCoarserCells) {
    const std::vector<Vec2d> pts = {{0, 0}, {1000, 1000}};
    const PlaneRaster r = rasterise_points(pts, 0.001, 0.0);
    EXPECT_LE(std::size_t(r.width) * std::size_t(r.height), kMaxRasterCells);
    EXPECT_EQ(r.occupied(), 2u);
}

TEST(BoundaryPolygon, SquareGivesOneCounterClockwiseRingOfFourCorners) {
    const auto pts = grid(0, 0.1, 0, 0.1, 0.005, [](double, double) { return false; });
    const auto polys = trace_boundaries(rasterise_points(pts, 0.005, 0.0), 0.001);
    ASSERT_EQ(polys.size(), 1u);
    EXPECT_TRUE(polys[0].holes.empty());
    // Marching squares cuts each corner diagonally: 8 vertices, area (0.105)^2 - 4 corner halves.
    EXPECT_EQ(polys[0].outer.size(), 8u);
    EXPECT_GT(signed_area(polys[0].outer), 0);
    EXPECT_NEAR(polygon_area(polys[0]), 0.105 * 0.105 - 2 * 0.0025 * 0.0025, 1e-12);
}

TEST(BoundaryPolygon, HolesAreClockwiseAndInTheirRing) {
    const auto pts = grid(0, 0.3, 0, 0.2, 0.005, [](double x, double y) {
        return (x > 0.05 && x < 0.1 && y > 0.05 && y < 0.1) ||
               (x > 0.2 && x < 0.25 && y > 0.05 && y < 0.15);
    });
    const auto polys = trace_boundaries(rasterise_points(pts, 0.005, 0.0), 0.001);
    ASSERT_EQ(polys.size(), 1u);
    ASSERT_EQ(polys[0].holes.size(), 2u);
    for (const Ring& h : polys[0].holes) {
        EXPECT_LT(signed_area(h), 0);
        for (const Vec2d& v : h) EXPECT_TRUE(ring_contains(polys[0].outer, v));
    }
    EXPECT_TRUE(polygon_contains(polys[0], {0.15, 0.1}));
    EXPECT_FALSE(polygon_contains(polys[0], {0.075, 0.075}));
    EXPECT_FALSE(polygon_contains(polys[0], {0.225, 0.1}));
}

TEST(BoundaryPolygon, SeparatePiecesAreSeparatePolygonsAndIslandsInHolesToo) {
    // A frame with an island in its hole, and a separate square beside it.
    const auto pts = grid(0, 0.5, 0, 0.2, 0.005, [](double x, double y) {
        const bool frame = x <= 0.2 && !(x > 0.03 && x < 0.17 && y > 0.03 && y < 0.17);
        const bool island = x >= 0.08 && x <= 0.12 && y >= 0.08 && y <= 0.12;
        const bool square = x >= 0.3 && x <= 0.4 && y <= 0.1;
        return !(frame || island || square);
    });
    const auto polys = trace_boundaries(rasterise_points(pts, 0.005, 0.0), 0.001);
    ASSERT_EQ(polys.size(), 3u);
    std::size_t with_hole = 0;
    for (const auto& p : polys) with_hole += p.holes.size();
    EXPECT_EQ(with_hole, 1u);
}

TEST(BoundaryPolygon, DouglasPeuckerKeepsCornersAndDropsWithinTolerance) {
    // A square with a zigzag edge of amplitude 1 mm: at tolerance 2 mm only the corners remain.
    Ring ring;
    for (int i = 0; i <= 10; ++i) ring.emplace_back(0.01 * i, (i % 2) * 0.001);
    ring.emplace_back(0.1, 0.1);
    ring.emplace_back(0.0, 0.1);
    const Ring s = simplify_ring(ring, 0.002);
    EXPECT_EQ(s.size(), 4u);
    EXPECT_GT(signed_area(s), 0);
    for (const Vec2d& v : ring) {  // every dropped vertex within the tolerance of the result
        double best = 1e9;
        for (std::size_t i = 0; i < s.size(); ++i) {
            const Vec2d a = s[i], b = s[(i + 1) % s.size()];
            const double t = std::clamp((v - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
            best = std::min(best, (v - (a + t * (b - a))).norm());
        }
        EXPECT_LE(best, 0.002 + 1e-12);
    }
    EXPECT_EQ(simplify_ring(ring, 0.0).size(), ring.size());  // nothing collinear to drop
    EXPECT_EQ(simplify_ring({{0, 0}, {1, 0}, {1, 1}}, 10.0).size(), 3u);
}

TEST(Triangulation, ConvexAndConcavePolygonsCoverTheirArea) {
    PolygonWithHoles l;
    l.outer = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};
    const Triangulation t = triangulate(l);
    EXPECT_EQ(t.triangles.size(), 4u);
    EXPECT_NEAR(triangles_area(t), 6.0, 1e-12);
    for (const auto& tri : t.triangles)
        EXPECT_GT(orient2d(t.vertices[tri[0]], t.vertices[tri[1]], t.vertices[tri[2]]), 0);
    // Clockwise input is turned around.
    PolygonWithHoles cw;
    cw.outer.assign(l.outer.rbegin(), l.outer.rend());
    EXPECT_NEAR(triangles_area(triangulate(cw)), 6.0, 1e-12);
}

TEST(Triangulation, HolesAreLeftOut) {
    PolygonWithHoles p;
    p.outer = {{0, 0}, {10, 0}, {10, 6}, {0, 6}};
    p.holes = {{{2, 2}, {4, 2}, {4, 4}, {2, 4}}, {{6, 1}, {8, 1}, {8, 5}, {6, 5}}};
    const Triangulation t = triangulate(p);
    EXPECT_EQ(t.vertices.size(), 12u);
    EXPECT_EQ(t.triangles.size(), 12u + 2 * 2 - 2);
    EXPECT_NEAR(triangles_area(t), polygon_area(p), 1e-9);
    EXPECT_NEAR(polygon_area(p), 60 - 4 - 8, 1e-12);
    for (const auto& tri : t.triangles) {  // no triangle inside a hole
        const Vec2d c = (t.vertices[tri[0]] + t.vertices[tri[1]] + t.vertices[tri[2]]) / 3;
        EXPECT_TRUE(polygon_contains(p, c)) << c.transpose();
    }
}

TEST(Triangulation, TracedPolygonsWithHolesTriangulateToTheirArea) {
    const auto pts = grid(0, 0.3, 0, 0.2, 0.005, [](double x, double y) {
        return (x > 0.05 && x < 0.1 && y > 0.05 && y < 0.1) || std::hypot(x - 0.2, y - 0.1) < 0.04;
    });
    const auto polys = trace_boundaries(rasterise_points(pts, 0.005, 0.005), 0.005);
    ASSERT_EQ(polys.size(), 1u);
    ASSERT_EQ(polys[0].holes.size(), 2u);
    const Triangulation t = triangulate(polys[0]);
    EXPECT_NEAR(triangles_area(t), polygon_area(polys[0]), 1e-9);
}

// Ears are tested against the loop's positions in a grid: on an outline of about 1,000 vertices
// with holes, every triangle is counter-clockwise, none lies in a hole, and they add up to the
// polygon's area, n + 2 h - 2 of them.
TEST(Triangulation, LongOutlinesWithHolesTriangulateToTheirArea) {
    // A comb of 60 teeth along the top of a 3 m x 1 m wall, its bottom edge cut into 600 steps,
    // two round holes of 300 vertices and a square one.
    PolygonWithHoles p;
    for (int k = 0; k <= 600; ++k) p.outer.push_back({0.005 * k, 0.001 * (k % 2)});
    for (int k = 59; k >= 0; --k) {
        const double x = 0.05 * k;
        p.outer.push_back({x + 0.05, 1.0});
        p.outer.push_back({x + 0.03, 1.0});
        p.outer.push_back({x + 0.03, 1.1});
        p.outer.push_back({x + 0.01, 1.1});
        p.outer.push_back({x + 0.01, 1.0});
    }
    p.outer.push_back({0.0, 1.0});
    auto circle = [](Vec2d c, double r, int n) {
        Ring ring;
        for (int k = 0; k < n; ++k) {
            const double t = -2 * 3.14159265358979 * k / n;  // clockwise, as holes are
            ring.push_back(c + r * Vec2d(std::cos(t), std::sin(t)));
        }
        return ring;
    };
    p.holes = {circle({0.7, 0.5}, 0.2, 300),
               circle({1.5, 0.4}, 0.15, 300),
               {{2.0, 0.3}, {2.0, 0.7}, {2.4, 0.7}, {2.4, 0.3}}};
    std::size_t n = p.outer.size();
    for (const Ring& h : p.holes) n += h.size();
    ASSERT_GT(n, 1000u);
    const Triangulation t = triangulate(p);
    EXPECT_EQ(t.triangles.size(), n + 2 * p.holes.size() - 2);
    EXPECT_NEAR(triangles_area(t), polygon_area(p), 1e-9);
    for (const auto& tri : t.triangles) {
        const Vec2d &a = t.vertices[tri[0]], &b = t.vertices[tri[1]], &c = t.vertices[tri[2]];
        EXPECT_GT(orient2d(a, b, c), 0);
        EXPECT_TRUE(polygon_contains(p, (a + b + c) / 3));
    }
}

TEST(Triangulation, DegenerateInputNeverFails) {
    PolygonWithHoles p;
    EXPECT_TRUE(triangulate(p).triangles.empty());
    p.outer = {{0, 0}, {1, 0}, {2, 0}};  // collinear
    EXPECT_TRUE(triangulate(p).triangles.empty());
    p.outer = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};  // a bow tie
    (void)triangulate(p);
    p.outer = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    p.holes = {{{5, 5}, {6, 5}, {6, 6}}};  // a hole outside its ring
    EXPECT_FALSE(triangulate(p).triangles.empty());
}

TEST(PolygonRaster, ScanlineFillMatchesPointInPolygon) {
    PolygonWithHoles p;
    p.outer = {{0, 0}, {0.3, 0}, {0.3, 0.1}, {0.1, 0.1}, {0.1, 0.25}, {0, 0.25}};
    p.holes = {{{0.02, 0.02}, {0.02, 0.06}, {0.06, 0.06}, {0.06, 0.02}}};
    const std::vector<PolygonWithHoles> polys{p};
    const PlaneRaster r = rasterise_polygons(polys, 0.007, Vec2d(0.001, 0.002));
    std::size_t inside = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            EXPECT_EQ(r.at(x, y), polygon_contains(p, r.centre(x, y)))
                << r.centre(x, y).transpose();
            inside += r.at(x, y);
        }
    EXPECT_NEAR(double(inside) * 0.007 * 0.007, polygon_area(p), 0.05 * polygon_area(p));
    EXPECT_EQ(rasterise_polygons({}, 0.01).width, 0);
}

// The scanline fill visits only the edges active on a row. Its cells must be those of the plain
// fill that tests every edge on every row (the oracle below), on outlines of many edges whose
// vertices fall on the rows' centres, between them, and on horizontal runs, with holes, several
// polygons at once; and within a cell of the even-odd point-in-polygon test.
TEST(PolygonRaster, ActiveEdgesGiveTheCellsOfEveryEdgeOnEveryRow) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 40; ++trial) {
        const double cell = 0.004 + 0.006 * u(rng);
        const bool on_rows = trial % 2 == 0;  // vertices on the rows' centres: the half-open rule
        auto star = [&](Vec2d centre, double radius, int n) {
            Ring ring;
            for (int k = 0; k < n; ++k) {
                const double t = 2 * 3.14159265358979 * k / n;
                const double rr = radius * (0.5 + 0.5 * u(rng));
                Vec2d q = centre + rr * Vec2d(std::cos(t), std::sin(t));
                if (on_rows) q.y() = std::round(q.y() / cell) * cell;
                if (k % 7 == 3 && !ring.empty()) q.y() = ring.back().y();  // a horizontal edge
                ring.push_back(q);
            }
            return ring;
        };
        std::vector<PolygonWithHoles> polys(3);
        for (int k = 0; k < 3; ++k) {
            const Vec2d c(0.7 * k, 0.2 * k);
            polys[static_cast<std::size_t>(k)].outer = star(c, 0.3, 50 + 200 * k);
            polys[static_cast<std::size_t>(k)].holes = {star(c, 0.06, 9)};
        }
        const Vec2d phase(on_rows ? 0.0 : 0.3 * cell, on_rows ? 0.0 : 0.7 * cell);
        const PlaneRaster r = rasterise_polygons(polys, cell, phase);
        ASSERT_GT(r.width, 0);
        // The oracle: every edge of every ring on every row.
        std::size_t differ = 0, off_contains = 0;
        for (int y = 0; y < r.height; ++y) {
            const double cy = r.origin.y() + y * r.cell;
            std::vector<double> xs;
            auto crossings = [&](const Ring& ring) {
                for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
                    const Vec2d &a = ring[i], &b = ring[j];
                    if ((a.y() > cy) != (b.y() > cy))
                        xs.push_back(a.x() + (cy - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
                }
            };
            for (const PolygonWithHoles& p : polys) {
                crossings(p.outer);
                for (const Ring& h : p.holes) crossings(h);
            }
            std::sort(xs.begin(), xs.end());
            std::vector<std::uint8_t> row(static_cast<std::size_t>(r.width), 0);
            for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
                const double from = std::ceil((xs[k] - r.origin.x()) / r.cell);
                const double to = std::ceil((xs[k + 1] - r.origin.x()) / r.cell);
                for (int x = static_cast<int>(std::max(0.0, from));
                     x < static_cast<int>(std::min<double>(r.width, to)); ++x)
                    row[static_cast<std::size_t>(x)] = 1;
            }
            for (int x = 0; x < r.width; ++x) {
                differ += r.at(x, y) != row[static_cast<std::size_t>(x)];
                bool in = false;
                for (const PolygonWithHoles& p : polys)
                    in = in || polygon_contains(p, r.centre(x, y));
                off_contains += r.at(x, y) != in;
            }
        }
        EXPECT_EQ(differ, 0u) << "trial " << trial;
        // Cells whose centre lies on an edge may go either way in the two tests: a few.
        EXPECT_LE(off_contains, 0.002 * r.width * r.height) << "trial " << trial;
    }
}

}  // namespace
}  // namespace surfgrow
