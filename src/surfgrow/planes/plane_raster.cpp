#include "surfgrow/planes/plane_raster.hpp"

#include <algorithm>
#include <cmath>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

namespace {

constexpr double kFar = 1e30;  // "no feature": finite, so the envelope arithmetic never sees inf

// Lower envelope of parabolas (Felzenszwalb & Huttenlocher 2012), one line of n samples.
void distance_1d(const double* f, int n, double* d, int* v, double* z) {
    int k = 0;
    v[0] = 0;
    z[0] = -kFar;
    z[1] = kFar;
    for (int q = 1; q < n; ++q) {
        const double fq = f[q] + double(q) * q;
        double s = (fq - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]));
        while (s <= z[k]) {
            --k;
            s = (fq - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]));
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = kFar;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        const double dq = q - v[k];
        d[q] = std::min(dq * dq + f[v[k]], kFar);
    }
}

// Grows `cell` until the box [lo, hi] fits in kMaxRasterCells cells with `margin_len` around it.
double fitting_cell(const Vec2d& lo, const Vec2d& hi, double cell, double margin_len) {
    // No fitting cell is finer than this (a side of more than kMaxRasterCells cells never fits):
    // starting there keeps w * h finite for a cell of 1e-300 (which once overflowed to a NaN
    // raster), and changes no cell that fits.
    const double side = std::max(hi.x() - lo.x(), hi.y() - lo.y()) + 2 * margin_len;
    cell = std::max(cell, side / double(kMaxRasterCells));
    for (int guard = 0; guard < 64; ++guard) {
        const double w = std::floor((hi.x() - lo.x() + 2 * margin_len) / cell) + 5;
        const double h = std::floor((hi.y() - lo.y() + 2 * margin_len) / cell) + 5;
        if (w * h <= double(kMaxRasterCells)) return cell;
        cell *= std::max(1.01, std::sqrt(w * h / double(kMaxRasterCells)));
    }
    throw Error(ErrorCode::kInvalidParameter, "raster: the extent is too large to rasterise");
}

}  // namespace

std::size_t PlaneRaster::occupied() const {
    return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), std::uint8_t{1}));
}

void squared_distance_transform(std::span<const std::uint8_t> feature, int width, int height,
                                std::vector<double>& out) {
    const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
    out.assign(w * h, kFar);
    for (std::size_t i = 0; i < w * h; ++i)
        if (feature[i]) out[i] = 0.0;
    const std::size_t n = std::max(w, h);
    std::vector<double> f(n), d(n), z(n + 1);
    std::vector<int> v(n);
    for (std::size_t y = 0; y < h; ++y) {
        double* row = out.data() + y * w;
        std::copy(row, row + w, f.begin());
        distance_1d(f.data(), width, row, v.data(), z.data());
    }
    for (std::size_t x = 0; x < w; ++x) {
        for (std::size_t y = 0; y < h; ++y) f[y] = out[y * w + x];
        distance_1d(f.data(), height, d.data(), v.data(), z.data());
        for (std::size_t y = 0; y < h; ++y) out[y * w + x] = d[y];
    }
}

namespace {

void check_lengths(double cell, double closing_radius) {
    if (!(cell > 0) || !std::isfinite(cell))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"raster cell must be positive, got ", num(cell)}));
    if (!(closing_radius >= 0) || !std::isfinite(closing_radius))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"closing radius must be >= 0, got ", num(closing_radius)}));
}

// The empty cells a closing by `closing_radius` needs beyond the marked ones.
int closing_margin(double closing_radius, double cell) {
    return static_cast<int>(std::ceil(closing_radius / cell)) + 2;
}

}  // namespace

PlaneRaster mark_points(std::span<const Vec2d> points, double cell, double closing_radius) {
    check_lengths(cell, closing_radius);
    if (points.empty()) throw Error(ErrorCode::kInvalidParameter, "raster: no points");
    Vec2d lo = points[0], hi = points[0];
    for (const Vec2d& p : points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    PlaneRaster r;
    r.cell = fitting_cell(lo, hi, cell, closing_radius);
    const int margin = closing_margin(closing_radius, r.cell);
    r.origin = lo - margin * r.cell * Vec2d::Ones();
    r.width = static_cast<int>(std::floor((hi.x() - lo.x()) / r.cell)) + 2 * margin + 2;
    r.height = static_cast<int>(std::floor((hi.y() - lo.y()) / r.cell)) + 2 * margin + 2;
    const std::size_t w = static_cast<std::size_t>(r.width);
    r.cells.assign(w * static_cast<std::size_t>(r.height), 0);
    for (const Vec2d& p : points) {
        const auto x = static_cast<std::size_t>(std::lround((p.x() - r.origin.x()) / r.cell));
        const auto y = static_cast<std::size_t>(std::lround((p.y() - r.origin.y()) / r.cell));
        r.cells[y * w + x] = 1;
    }
    return r;
}

void close_gaps(PlaneRaster& r, double closing_radius) {
    check_lengths(r.cell, closing_radius);
    if (closing_radius <= 0) return;
    // Closing = dilation then erosion by the same disc; both are thresholds of a distance map.
    const double r2 = (closing_radius / r.cell) * (closing_radius / r.cell);
    std::vector<double> dist;
    squared_distance_transform(r.cells, r.width, r.height, dist);
    std::vector<std::uint8_t> outside(r.cells.size());
    for (std::size_t i = 0; i < dist.size(); ++i) outside[i] = dist[i] > r2 ? 1 : 0;
    squared_distance_transform(outside, r.width, r.height, dist);
    for (std::size_t i = 0; i < dist.size(); ++i) r.cells[i] = dist[i] > r2 ? 1 : 0;
}

PlaneRaster rasterise_points(std::span<const Vec2d> points, double cell, double closing_radius) {
    PlaneRaster r = mark_points(points, cell, closing_radius);
    close_gaps(r, closing_radius);
    return r;
}

PlaneRaster rasterise_polygons(std::span<const PolygonWithHoles> polygons, double cell,
                               const Vec2d& phase) {
    if (!(cell > 0) || !std::isfinite(cell))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"raster cell must be positive, got ", num(cell)}));
    PlaneRaster r;
    r.cell = cell;
    Vec2d lo = Vec2d::Constant(kFar), hi = Vec2d::Constant(-kFar);
    std::size_t edges = 0;
    for (const PolygonWithHoles& p : polygons) {
        for (const Vec2d& q : p.outer) {
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
        }
        edges += p.outer.size();
        for (const Ring& h : p.holes) edges += h.size();
    }
    if (edges == 0 || !(lo.x() <= hi.x())) return r;
    r.cell = fitting_cell(lo, hi, cell, 0.0);
    const Vec2d base = phase - r.cell * ((phase - lo) / r.cell).array().floor().matrix();
    r.origin = base;
    r.width = static_cast<int>(std::floor((hi.x() - base.x()) / r.cell)) + 1;
    r.height = static_cast<int>(std::floor((hi.y() - base.y()) / r.cell)) + 1;
    const std::size_t w = static_cast<std::size_t>(r.width);
    r.cells.assign(w * static_cast<std::size_t>(r.height), 0);
    // Scanline fill over an active edge list: each edge is visited on the rows it spans, not on
    // every row (a wall's outline has thousands of edges and its raster thousands of rows).
    // Edge (a, b) crosses row y where (a.y > y) != (b.y > y), at the x below, as before.
    struct Edge {
        Vec2d a, b;
        int first = 0;  // first row it may cross
    };
    auto row_y = [&](int y) { return base.y() + y * r.cell; };
    std::vector<Edge> edges_by_row;
    edges_by_row.reserve(edges);
    auto add_ring = [&](const Ring& ring) {
        const std::size_t n = ring.size();
        for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
            const Vec2d& a = ring[i];
            const Vec2d& b = ring[j];
            if (a.y() == b.y()) continue;  // horizontal: crosses no row
            const double lo_y = std::min(a.y(), b.y());
            // The first row at or above the edge's lower end (rounding checked on the rows).
            int y = static_cast<int>(std::clamp(std::floor((lo_y - base.y()) / r.cell), -1.0,
                                                static_cast<double>(r.height)));
            while (y > 0 && row_y(y - 1) >= lo_y) --y;
            while (y < r.height && row_y(y) < lo_y) ++y;
            edges_by_row.push_back({a, b, std::max(y, 0)});
        }
    };
    for (const PolygonWithHoles& p : polygons) {
        add_ring(p.outer);
        for (const Ring& h : p.holes) add_ring(h);
    }
    std::stable_sort(edges_by_row.begin(), edges_by_row.end(),
                     [](const Edge& u, const Edge& v) { return u.first < v.first; });
    std::vector<const Edge*> active;
    std::vector<double> xs;
    xs.reserve(64);
    std::size_t next = 0;
    for (int y = 0; y < r.height; ++y) {
        const double cy = row_y(y);
        while (next < edges_by_row.size() && edges_by_row[next].first <= y)
            active.push_back(&edges_by_row[next++]);
        xs.clear();
        std::size_t kept = 0;
        for (const Edge* e : active) {
            const Vec2d& a = e->a;
            const Vec2d& b = e->b;
            if (std::max(a.y(), b.y()) <= cy) continue;  // passed: never crosses a row again
            active[kept++] = e;
            if ((a.y() > cy) != (b.y() > cy))
                xs.push_back(a.x() + (cy - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
        }
        active.resize(kept);
        std::sort(xs.begin(), xs.end());
        for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
            const double from = std::ceil((xs[k] - base.x()) / r.cell);
            const double to = std::ceil((xs[k + 1] - base.x()) / r.cell);  // exclusive
            const int x0 = static_cast<int>(std::max(0.0, from));
            const int x1 = static_cast<int>(std::min<double>(r.width, to));
            for (int x = x0; x < x1; ++x)
                r.cells[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] = 1;
        }
    }
    return r;
}

}  // namespace surfgrow
