#include "surfgrow/planes/polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surfgrow {

namespace {

using Index = std::uint32_t;

bool in_triangle(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& q) {
    return orient2d(a, b, q) >= 0 && orient2d(b, c, q) >= 0 && orient2d(c, a, q) >= 0;
}

// Where in `loop` (a closed sequence of vertex indices) hole vertex m connects: the vertex of
// the first edge a ray from m towards +x meets, or a reflex vertex that hides it (Eberly).
std::size_t bridge_target(const std::vector<Vec2d>& v, const std::vector<Index>& loop, Index m) {
    const Vec2d& M = v[m];
    const std::size_t n = loop.size();
    double best_x = std::numeric_limits<double>::infinity();
    std::size_t hit = n;  // the loop position of the edge's vertex with the larger x
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2d& a = v[loop[i]];
        const Vec2d& b = v[loop[(i + 1) % n]];
        if (a.y() == b.y()) continue;  // parallel to the ray
        if (std::min(a.y(), b.y()) > M.y() || std::max(a.y(), b.y()) < M.y()) continue;
        const double x = a.x() + (M.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (x < M.x() || x >= best_x) continue;
        best_x = x;
        hit = a.x() >= b.x() ? i : (i + 1) % n;
    }
    if (hit == n) {  // not inside the ring (not a simple polygon): join the nearest vertex
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < n; ++i) {
            const double d = (v[loop[i]] - M).squaredNorm();
            if (d < best) {
                best = d;
                hit = i;
            }
        }
        return hit;
    }
    const Vec2d I(best_x, M.y());
    const Vec2d P = v[loop[hit]];
    if (P == I) return hit;
    // Reflex vertices inside triangle (M, I, P) would block the bridge: take the one at the
    // smallest angle from the ray (then the nearest).
    const bool ccw = orient2d(M, I, P) > 0;
    std::size_t best_pos = hit;
    double best_tan = std::numeric_limits<double>::infinity(), best_d = best_tan;
    for (std::size_t i = 0; i < n; ++i) {
        if (i == hit) continue;
        const Vec2d& q = v[loop[i]];
        const Vec2d& prev = v[loop[(i + n - 1) % n]];
        const Vec2d& next = v[loop[(i + 1) % n]];
        if (orient2d(prev, q, next) > 0) continue;  // convex
        const bool inside = ccw ? in_triangle(M, I, P, q) : in_triangle(M, P, I, q);
        if (!inside || q.x() <= M.x()) continue;
        const double tan = std::abs(q.y() - M.y()) / (q.x() - M.x());
        const double d = (q - M).squaredNorm();
        if (tan < best_tan || (tan == best_tan && d < best_d)) {
            best_tan = tan;
            best_d = d;
            best_pos = i;
        }
    }
    return best_pos;
}

}  // namespace

Triangulation triangulate(const PolygonWithHoles& polygon) {
    Triangulation t;
    if (polygon.outer.size() < 3) return t;
    // Outer ring counter-clockwise, holes clockwise, all in one vertex list.
    auto append = [&](const Ring& ring, bool want_ccw) {
        const auto first = static_cast<Index>(t.vertices.size());
        const bool ccw = signed_area(ring) > 0;
        if (ccw == want_ccw)
            t.vertices.insert(t.vertices.end(), ring.begin(), ring.end());
        else
            t.vertices.insert(t.vertices.end(), ring.rbegin(), ring.rend());
        return first;
    };
    std::vector<Index> loop(polygon.outer.size());
    for (Index i = 0; i < loop.size(); ++i) loop[i] = i;
    append(polygon.outer, true);
    struct Hole {
        Index first, size, rightmost;
    };
    std::vector<Hole> holes;
    for (const Ring& h : polygon.holes) {
        if (h.size() < 3) continue;
        const Index first = append(h, false);
        Index right = first;
        for (Index i = first; i < t.vertices.size(); ++i)
            if (t.vertices[i].x() > t.vertices[right].x() ||
                (t.vertices[i].x() == t.vertices[right].x() &&
                 t.vertices[i].y() < t.vertices[right].y()))
                right = i;
        holes.push_back({first, static_cast<Index>(h.size()), right});
    }
    // Bridge holes in from the rightmost one: each bridge then sees only rings already joined.
    std::stable_sort(holes.begin(), holes.end(), [&](const Hole& a, const Hole& b) {
        return t.vertices[a.rightmost].x() > t.vertices[b.rightmost].x();
    });
    for (const Hole& h : holes) {
        const std::size_t pos = bridge_target(t.vertices, loop, h.rightmost);
        std::vector<Index> spliced;
        spliced.reserve(loop.size() + h.size + 2);
        spliced.insert(spliced.end(), loop.begin(), loop.begin() + static_cast<long>(pos) + 1);
        for (Index k = 0; k <= h.size; ++k)
            spliced.push_back(h.first + (h.rightmost - h.first + k) % h.size);
        spliced.push_back(loop[pos]);
        spliced.insert(spliced.end(), loop.begin() + static_cast<long>(pos) + 1, loop.end());
        loop = std::move(spliced);
    }
    // Ear clipping over a linked list of loop positions.
    const std::size_t n = loop.size();
    std::vector<std::size_t> prev(n), next(n);
    for (std::size_t i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    const std::vector<Vec2d>& v = t.vertices;
    auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
        if (orient2d(v[loop[a]], v[loop[b]], v[loop[c]]) > 0)
            t.triangles.push_back({loop[a], loop[b], loop[c]});
    };
    // The loop's positions in a grid of about one per cell, so that an ear is tested against
    // the positions near it rather than the whole loop (a wall's outline has thousands). A
    // clipped position is dead: the same positions are tested as a walk round the loop would.
    Vec2d glo = Vec2d::Constant(std::numeric_limits<double>::infinity()), ghi = -glo;
    for (const Index i : loop) {
        glo = glo.cwiseMin(v[i]);
        ghi = ghi.cwiseMax(v[i]);
    }
    const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n))));
    const Vec2d extent = (ghi - glo).cwiseMax(Vec2d::Constant(1e-300));
    auto cell_of = [&](const Vec2d& q, int axis) {
        const double f = (q[axis] - glo[axis]) / extent[axis] * side;
        return std::clamp(static_cast<int>(std::isfinite(f) ? f : 0.0), 0, side - 1);
    };
    auto cell_index = [&](int gx, int gy) {
        return static_cast<std::size_t>(gy) * static_cast<std::size_t>(side) +
               static_cast<std::size_t>(gx);
    };
    auto cell_of_position = [&](std::size_t i) {
        return cell_index(cell_of(v[loop[i]], 0), cell_of(v[loop[i]], 1));
    };
    std::vector<std::size_t> start(static_cast<std::size_t>(side) * side + 1, 0), members(n);
    for (std::size_t i = 0; i < n; ++i) ++start[cell_of_position(i) + 1];
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    {
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < n; ++i) members[fill[cell_of_position(i)]++] = i;
    }
    std::vector<std::uint8_t> alive(n, 1);
    auto is_ear = [&](std::size_t b) {
        const std::size_t a = prev[b], c = next[b];
        const Vec2d &A = v[loop[a]], &B = v[loop[b]], &C = v[loop[c]];
        if (orient2d(A, B, C) <= 0) return false;
        const Vec2d lo = A.cwiseMin(B).cwiseMin(C), hi = A.cwiseMax(B).cwiseMax(C);
        const int x0 = cell_of(lo, 0), x1 = cell_of(hi, 0), y0 = cell_of(lo, 1),
                  y1 = cell_of(hi, 1);
        for (int gy = y0; gy <= y1; ++gy)
            for (int gx = x0; gx <= x1; ++gx) {
                const std::size_t g = cell_index(gx, gy);
                for (std::size_t m = start[g]; m < start[g + 1]; ++m) {
                    const std::size_t k = members[m];
                    if (!alive[k] || k == a || k == b || k == c) continue;
                    const Vec2d& q = v[loop[k]];
                    if (q.x() < lo.x() || q.y() < lo.y() || q.x() > hi.x() || q.y() > hi.y())
                        continue;
                    if (q == A || q == B || q == C) continue;  // a bridge's duplicate
                    if (in_triangle(A, B, C, q)) return false;
                }
            }
        return true;
    };
    std::size_t remaining = n, cur = 0, stalled = 0;
    t.triangles.reserve(n);
    while (remaining > 3) {
        const bool ear = is_ear(cur);
        if (ear || stalled >= remaining) {  // no ear in a whole lap: not simple; cut anyway
            emit(prev[cur], cur, next[cur]);
            next[prev[cur]] = next[cur];
            prev[next[cur]] = prev[cur];
            alive[cur] = 0;
            --remaining;
            cur = prev[cur];
            stalled = 0;
        } else {
            cur = next[cur];
            ++stalled;
        }
    }
    emit(prev[cur], cur, next[cur]);
    return t;
}

}  // namespace surfgrow
