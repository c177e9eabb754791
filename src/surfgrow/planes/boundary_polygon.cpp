#include "surfgrow/planes/boundary_polygon.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace surfgrow {

namespace {

using EdgeId = std::uint64_t;

// A contour vertex sits at the midpoint of a lattice edge between two cell centres: the edge
// from (x, y) to (x + 1, y) is 2 * (y * width + x), the one from (x, y) to (x, y + 1) is that + 1.
struct Segment {
    EdgeId from;
    EdgeId to;
};

// Directed contour segments, occupied side on the left, from every 2x2 block of cell centres.
std::vector<Segment> march(const PlaneRaster& r) {
    std::vector<Segment> segs;
    const auto w = static_cast<EdgeId>(r.width);
    for (int y = 0; y + 1 < r.height; ++y) {
        for (int x = 0; x + 1 < r.width; ++x) {
            // Corners counter-clockwise from bottom-left; block edge k joins corner k to k + 1.
            const bool c[4] = {r.at(x, y), r.at(x + 1, y), r.at(x + 1, y + 1), r.at(x, y + 1)};
            if (c[0] == c[1] && c[1] == c[2] && c[2] == c[3]) continue;
            const EdgeId base = 2 * (static_cast<EdgeId>(y) * w + static_cast<EdgeId>(x));
            const EdgeId edge[4] = {base, base + 2 * 1 + 1, base + 2 * w, base + 1};
            // From each edge crossed occupied -> empty, walk counter-clockwise to the next edge
            // crossed empty -> occupied. At a saddle this joins the occupied diagonal.
            for (int k = 0; k < 4; ++k) {
                if (!(c[k] && !c[(k + 1) % 4])) continue;
                for (int j = 1; j < 4; ++j) {
                    const int e = (k + j) % 4;
                    if (!c[e] && c[(e + 1) % 4]) {
                        segs.push_back({edge[k], edge[e]});
                        break;
                    }
                }
            }
        }
    }
    return segs;
}

Vec2d edge_midpoint(const PlaneRaster& r, EdgeId id) {
    const EdgeId cell = id / 2;
    const auto w = static_cast<EdgeId>(r.width);
    const double x = double(cell % w), y = double(cell / w);
    return (id & 1) ? r.centre(x, y + 0.5) : r.centre(x + 0.5, y);
}

// Links the segments into closed rings, starting from the lowest unvisited start id.
std::vector<Ring> link_rings(const PlaneRaster& r, std::vector<Segment>& segs) {
    std::sort(segs.begin(), segs.end(),
              [](const Segment& a, const Segment& b) { return a.from < b.from; });
    std::vector<std::uint8_t> used(segs.size(), 0);
    auto find = [&](EdgeId from) -> std::size_t {
        const auto it = std::lower_bound(segs.begin(), segs.end(), from,
                                         [](const Segment& s, EdgeId v) { return s.from < v; });
        return it != segs.end() && it->from == from ? std::size_t(it - segs.begin()) : segs.size();
    };
    std::vector<Ring> rings;
    for (std::size_t s = 0; s < segs.size(); ++s) {
        if (used[s]) continue;
        Ring ring;
        std::size_t k = s;
        while (k < segs.size() && !used[k]) {
            used[k] = 1;
            ring.push_back(edge_midpoint(r, segs[k].from));
            k = find(segs[k].to);
        }
        if (ring.size() >= 3) rings.push_back(std::move(ring));
    }
    return rings;
}

// Lowest, then leftmost vertex.
std::size_t anchor_of(const Ring& ring) {
    std::size_t a = 0;
    for (std::size_t i = 1; i < ring.size(); ++i)
        if (ring[i].y() < ring[a].y() || (ring[i].y() == ring[a].y() && ring[i].x() < ring[a].x()))
            a = i;
    return a;
}

double segment_distance(const Vec2d& p, const Vec2d& a, const Vec2d& b) {
    const Vec2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

// Douglas-Peucker on ring[first..last] (indices modulo n), marking kept vertices.
void simplify_chain(const Ring& ring, std::size_t first, std::size_t last, double tol,
                    std::vector<std::uint8_t>& keep,
                    std::vector<std::pair<std::size_t, std::size_t>>& stack) {
    const std::size_t n = ring.size();
    stack.clear();
    stack.emplace_back(first, last);
    while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        const std::size_t span = (b + n - a) % n;
        if (span < 2) continue;
        double worst = -1;
        std::size_t at = a;
        for (std::size_t j = 1; j < span; ++j) {
            const std::size_t i = (a + j) % n;
            const double d = segment_distance(ring[i], ring[a], ring[b % n]);
            if (d > worst) {
                worst = d;
                at = i;
            }
        }
        if (worst > tol) {
            keep[at] = 1;
            stack.emplace_back(a, at);
            stack.emplace_back(at, b);
        }
    }
}

}  // namespace

Ring simplify_ring(const Ring& input, double tolerance) {
    // Repeated vertices first: they would make zero-length chords.
    Ring ring;
    ring.reserve(input.size());
    for (const Vec2d& p : input)
        if (ring.empty() || p != ring.back()) ring.push_back(p);
    while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    const std::size_t n = ring.size();
    if (n <= 3) return ring;
    const std::size_t a = anchor_of(ring);
    std::size_t b = a;
    double far = -1;
    for (std::size_t i = 0; i < n; ++i) {
        const double d = (ring[i] - ring[a]).squaredNorm();
        if (d > far) {
            far = d;
            b = i;
        }
    }
    std::vector<std::uint8_t> keep(n, 0);
    keep[a] = keep[b] = 1;
    std::vector<std::pair<std::size_t, std::size_t>> stack;
    const double tol = std::max(tolerance, 0.0);
    simplify_chain(ring, a, b, tol, keep, stack);
    simplify_chain(ring, b, a, tol, keep, stack);
    Ring out;
    for (std::size_t j = 0; j < n; ++j) {
        const std::size_t i = (a + j) % n;
        if (keep[i]) out.push_back(ring[i]);
    }
    if (out.size() < 3) {  // a sliver: keep the vertex farthest from the chord a-b
        std::size_t best = a;
        double worst = -1;
        for (std::size_t i = 0; i < n; ++i) {
            const double d = segment_distance(ring[i], ring[a], ring[b]);
            if (!keep[i] && d > worst) {
                worst = d;
                best = i;
            }
        }
        keep[best] = 1;
        out.clear();
        for (std::size_t j = 0; j < n; ++j)
            if (keep[(a + j) % n]) out.push_back(ring[(a + j) % n]);
    }
    return out;
}

std::vector<PolygonWithHoles> trace_boundaries(const PlaneRaster& raster, double simplify_tolerance,
                                               double min_hole_area) {
    std::vector<Segment> segs = march(raster);
    std::vector<Ring> rings = link_rings(raster, segs);
    std::vector<PolygonWithHoles> polygons;
    std::vector<double> outer_area;
    std::vector<std::pair<Vec2d, Vec2d>> outer_box;
    std::vector<const Ring*> holes;
    for (Ring& ring : rings) {
        const double a = signed_area(ring);
        if (a > 0) {
            Vec2d lo = ring[0], hi = ring[0];
            for (const Vec2d& p : ring) {
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
            polygons.push_back({std::move(ring), {}});
            outer_area.push_back(a);
            outer_box.emplace_back(lo, hi);
        } else if (-a >= min_hole_area) {
            holes.push_back(&ring);
        }
    }
    // Each hole belongs to the smallest outer ring around it (rings never cross, so one vertex
    // decides). Nesting is tested on the exact rings, before simplification.
    for (const Ring* hole : holes) {
        const Vec2d& q = (*hole)[0];
        std::size_t best = polygons.size();
        for (std::size_t k = 0; k < polygons.size(); ++k) {
            const auto& [lo, hi] = outer_box[k];
            if (q.x() < lo.x() || q.y() < lo.y() || q.x() > hi.x() || q.y() > hi.y()) continue;
            if ((best == polygons.size() || outer_area[k] < outer_area[best]) &&
                ring_contains(polygons[k].outer, q))
                best = k;
        }
        if (best < polygons.size()) polygons[best].holes.push_back(*hole);
    }
    for (PolygonWithHoles& p : polygons) {
        p.outer = simplify_ring(p.outer, simplify_tolerance);
        for (Ring& h : p.holes) h = simplify_ring(h, simplify_tolerance);
        std::erase_if(p.holes, [](const Ring& h) { return h.size() < 3; });
        std::sort(p.holes.begin(), p.holes.end(), [](const Ring& x, const Ring& y) {
            const Vec2d &a = x[anchor_of(x)], &b = y[anchor_of(y)];
            return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x());
        });
    }
    std::sort(polygons.begin(), polygons.end(),
              [](const PolygonWithHoles& x, const PolygonWithHoles& y) {
                  const Vec2d &a = x.outer[anchor_of(x.outer)], &b = y.outer[anchor_of(y.outer)];
                  return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x());
              });
    return polygons;
}

}  // namespace surfgrow
