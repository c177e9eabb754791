#include "surfgrow/robot/coverage.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <queue>
#include <tuple>

#include "surfgrow/core/detail/parallel_errors.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/length_limits.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/planes/plane_raster.hpp"

namespace surfgrow {

namespace {

constexpr double kDeg = M_PI / 180.0;

[[noreturn]] void bad(std::initializer_list<std::string_view> what) {
    throw Error(ErrorCode::kInvalidParameter, cat(what));
}

// Calls f(cell index) for every cell of `r` whose centre lies within `radius` of c.
template <class F>
void for_each_cell_in_disc(const PlaneRaster& r, const Vec2d& c, double radius, F&& f) {
    if (r.width == 0) return;
    const double inv = 1.0 / r.cell;
    // Clamped to the raster before the cast: a disc far larger than the plane (a blast radius of
    // 1e38) gives cell numbers beyond int.
    auto cell_at_or_above = [](double v, int hi) {
        return static_cast<int>(std::clamp(std::ceil(v), 0.0, double(hi) + 1));
    };
    auto cell_at_or_below = [](double v, int hi) {
        return static_cast<int>(std::clamp(std::floor(v), -1.0, double(hi)));
    };
    const int y0 = cell_at_or_above((c.y() - radius - r.origin.y()) * inv, r.height - 1);
    const int y1 = cell_at_or_below((c.y() + radius - r.origin.y()) * inv, r.height - 1);
    for (int y = y0; y <= y1; ++y) {
        const double dy = r.origin.y() + y * r.cell - c.y();
        const double rem = radius * radius - dy * dy;
        if (rem < 0) continue;
        const double hw = std::sqrt(rem);
        const int x0 = cell_at_or_above((c.x() - hw - r.origin.x()) * inv, r.width - 1);
        const int x1 = cell_at_or_below((c.x() + hw - r.origin.x()) * inv, r.width - 1);
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width);
        for (int x = x0; x <= x1; ++x) f(row + static_cast<std::size_t>(x));
    }
}

// Whether p lies on the plane's area: the raster cell nearest to it is occupied.
bool on_surface(const PlaneRaster& r, const Vec2d& p) {
    const long x = std::lround((p.x() - r.origin.x()) / r.cell);
    const long y = std::lround((p.y() - r.origin.y()) / r.cell);
    return x >= 0 && y >= 0 && x < r.width && y < r.height &&
           r.at(static_cast<int>(x), static_cast<int>(y));
}

PlaneGoals cover_plane(const BoundPlane& plane, std::span<const Surface> surfaces, double b,
                       double spacing) {
    PlaneGoals g;
    const PlaneRaster samples = rasterise_polygons(plane.polygons, spacing);
    std::vector<std::uint8_t> covered(samples.cells.size(), 0);
    std::size_t uncovered = samples.occupied();
    const double row_step = 1.5 * b, col_step = std::sqrt(3.0) * b;
    const double y_base = samples.origin.y();
    auto gain = [&](const Vec2d& c) {
        std::size_t n = 0;
        for_each_cell_in_disc(samples, c, b,
                              [&](std::size_t i) { n += samples.cells[i] && !covered[i]; });
        return n;
    };
    auto take = [&](const Vec2d& c, std::uint32_t row, bool home) {
        for_each_cell_in_disc(samples, c, b, [&](std::size_t i) {
            if (samples.cells[i] && !covered[i]) {
                covered[i] = 1;
                --uncovered;
            }
        });
        g.points.push_back(c);
        g.rows.push_back(row);
        g.from_home.push_back(home ? 1 : 0);
    };
    auto row_of = [&](const Vec2d& c) {
        return static_cast<std::uint32_t>(std::max(0L, std::lround((c.y() - y_base) / row_step)));
    };
    // 1. The hexagonal lattice, rows along u from the lowest sample row.
    if (uncovered > 0) {
        const double x_lo = samples.origin.x() - col_step;
        const double x_hi = samples.origin.x() + samples.cell * samples.width + col_step;
        const double y_hi = y_base + samples.cell * samples.height + row_step;
        for (std::uint32_t k = 0; y_base + k * row_step <= y_hi; ++k) {
            const double y = y_base + k * row_step;
            for (double x = x_lo + (k % 2 ? 0.5 * col_step : 0.0); x <= x_hi; x += col_step) {
                const Vec2d c(x, y);
                if (on_surface(samples, c) && gain(c) > 0) take(c, k, false);
            }
        }
    }
    // 2. Lazy greedy over home points and grid points near what is left (along the boundary).
    if (uncovered > 0) {
        std::vector<Vec2d> cand;
        std::vector<std::uint8_t> is_home;
        for (const std::uint32_t s : plane.patches) {
            if (s >= surfaces.size()) continue;
            const Vec2d h = plane.to_plane(surfaces[s].home);
            if (on_surface(samples, h)) {
                cand.push_back(h);
                is_home.push_back(1);
            }
        }
        std::vector<std::uint8_t> near(samples.cells.size(), 0);
        for (int y = 0; y < samples.height; ++y)
            for (int x = 0; x < samples.width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(samples.width) + std::size_t(x);
                if (samples.cells[i] && !covered[i])
                    for_each_cell_in_disc(samples, samples.centre(x, y), b,
                                          [&](std::size_t j) { near[j] = 1; });
            }
        for (int y = 0; y < samples.height; ++y)
            for (int x = 0; x < samples.width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(samples.width) + std::size_t(x);
                if (near[i] && samples.cells[i]) {
                    cand.push_back(samples.centre(x, y));
                    is_home.push_back(0);
                }
            }
        // Largest gain first; then home points; then the lower index. Gains only shrink, so a
        // popped entry whose recomputed gain still matches its key is the true maximum.
        using Entry = std::tuple<std::size_t, std::uint8_t, std::size_t>;  // gain, home, -index
        auto worse = [](const Entry& x, const Entry& y) {
            if (std::get<0>(x) != std::get<0>(y)) return std::get<0>(x) < std::get<0>(y);
            if (std::get<1>(x) != std::get<1>(y)) return std::get<1>(x) < std::get<1>(y);
            return std::get<2>(x) > std::get<2>(y);
        };
        std::priority_queue<Entry, std::vector<Entry>, decltype(worse)> heap(worse);
        for (std::size_t c = 0; c < cand.size(); ++c)
            if (const std::size_t n = gain(cand[c]); n > 0) heap.emplace(n, is_home[c], c);
        while (uncovered > 0 && !heap.empty()) {
            const auto [old_gain, home, c] = heap.top();
            heap.pop();
            const std::size_t n = gain(cand[c]);
            if (n == 0) continue;
            if (n < old_gain) {
                heap.emplace(n, home, c);
                continue;
            }
            take(cand[c], row_of(cand[c]), home != 0);
        }
    }
    // A sliver with no grid point inside: one goal at its outer ring's mean vertex.
    if (g.points.empty() && !plane.polygons.empty() && !plane.polygons[0].outer.empty()) {
        Vec2d mean = Vec2d::Zero();
        for (const Vec2d& p : plane.polygons[0].outer) mean += p;
        mean /= double(plane.polygons[0].outer.size());
        take(mean, 0, false);
    }
    // Coverage on an independent grid, twice as fine and offset by a quarter cell.
    const double fine = 0.5 * samples.cell;
    const PlaneRaster eval = rasterise_polygons(plane.polygons, fine, Vec2d::Constant(0.5 * fine));
    std::vector<std::uint8_t> hit(eval.cells.size(), 0);
    for (const Vec2d& p : g.points)
        for_each_cell_in_disc(eval, p, b, [&](std::size_t i) { hit[i] = eval.cells[i]; });
    const std::size_t total = eval.occupied();
    const auto got = static_cast<std::size_t>(std::count(hit.begin(), hit.end(), std::uint8_t{1}));
    g.covered_fraction = total ? double(got) / double(total) : (g.points.empty() ? 0.0 : 1.0);
    return g;
}

bool same_rings(const std::vector<PolygonWithHoles>& a, const std::vector<PolygonWithHoles>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (a[k].outer != b[k].outer || a[k].holes != b[k].holes) return false;
    return true;
}

// The memo's goals of `plane` when it planned the same plane (what cover_plane reads: its frame,
// polygons and patches, and those patches' homes); null otherwise.
const PlaneGoals* remembered_goals(const CoverageMemo& memo, const BoundPlane& plane,
                                   std::span<const Surface> surfaces) {
    if (plane.patches.empty() || plane.patches[0] >= memo.plane_from.size()) return nullptr;
    const std::int32_t k = memo.plane_from[plane.patches[0]];
    if (k < 0) return nullptr;
    const CoverageMemo::Plane& m = memo.planes[static_cast<std::size_t>(k)];
    const BoundPlane& p = m.plane;
    if (p.patches != plane.patches || p.centroid != plane.centroid || p.u_axis != plane.u_axis ||
        p.v_axis != plane.v_axis || !same_rings(p.polygons, plane.polygons))
        return nullptr;
    for (std::size_t i = 0; i < plane.patches.size(); ++i) {
        const std::uint32_t s = plane.patches[i];
        if (s >= surfaces.size() || surfaces[s].home != m.homes[i]) return nullptr;
    }
    return &m.goals;
}

void remember_goals(CoverageMemo& memo, const BoundPlanes& planes,
                    std::span<const Surface> surfaces, std::vector<PlaneGoals> goals,
                    const CoverageConfig& cfg) {
    memo.blast_radius = cfg.blast_radius;
    memo.sample_spacing = cfg.sample_spacing;
    memo.planes.clear();
    memo.plane_from.assign(surfaces.size(), -1);
    for (std::size_t k = 0; k < planes.planes.size(); ++k) {
        const BoundPlane& p = planes.planes[k];
        CoverageMemo::Plane m;
        m.plane.centroid = p.centroid;
        m.plane.u_axis = p.u_axis;
        m.plane.v_axis = p.v_axis;
        m.plane.polygons = p.polygons;
        m.plane.patches = p.patches;
        bool homes = !p.patches.empty();
        for (const std::uint32_t s : p.patches) {
            if (s >= surfaces.size()) {
                homes = false;
                break;
            }
            m.homes.push_back(surfaces[s].home);
        }
        if (!homes) continue;
        m.goals = std::move(goals[k]);
        memo.plane_from[p.patches[0]] = static_cast<std::int32_t>(memo.planes.size());
        memo.planes.push_back(std::move(m));
    }
}

// A plane's goals in sweep order: rows ascending, alternating direction along u.
struct Sweep {
    std::uint32_t plane = 0;
    std::vector<std::uint32_t> order;  // indices into the plane's goals
    std::vector<double> dir;           // +1 / -1 along u, per entry of order
    bool reversed = false;             // run backwards (last goal first, directions negated)
    Vec3d entry[2], exit[2];           // tool positions, [forward, reversed]
};

Sweep make_sweep(std::uint32_t plane, const PlaneGoals& g) {
    Sweep s;
    s.plane = plane;
    s.order.reserve(g.points.size());
    for (std::uint32_t i = 0; i < g.points.size(); ++i) s.order.push_back(i);
    std::sort(s.order.begin(), s.order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (g.rows[a] != g.rows[b]) return g.rows[a] < g.rows[b];
        if (g.points[a].x() != g.points[b].x()) return g.points[a].x() < g.points[b].x();
        return a < b;
    });
    // Alternate by visited row: reverse every other run of equal rows.
    std::size_t begin = 0, parity = 0;
    while (begin < s.order.size()) {
        std::size_t end = begin;
        while (end < s.order.size() && g.rows[s.order[end]] == g.rows[s.order[begin]]) ++end;
        if (parity % 2) std::reverse(s.order.begin() + long(begin), s.order.begin() + long(end));
        s.dir.insert(s.dir.end(), end - begin, parity % 2 ? -1.0 : 1.0);
        ++parity;
        begin = end;
    }
    return s;
}

struct Pose {
    Vec3d tool, axis;
    Eigen::Quaterniond q;
};

Pose pose_at(const Vec3d& p, const Vec3d& n, const Vec3d& dir, double tilt, double standoff) {
    const Vec3d back = (std::cos(tilt) * n - std::sin(tilt) * dir).normalized();
    Pose pose;
    pose.tool = p + standoff * back;
    pose.axis = -back;
    const Vec3d z = pose.axis;
    Vec3d x = dir - dir.dot(z) * z;
    x = x.norm() > 1e-12 ? Vec3d(x.normalized()) : Vec3d(z.unitOrthogonal());
    Mat3d frame;
    frame << x, z.cross(x), z;
    pose.q = Eigen::Quaterniond(frame).normalized();
    if (pose.q.w() < 0) pose.q.coeffs() *= -1.0;
    return pose;
}

// Visiting order of the sweeps: nearest neighbour, then 2-opt with each sweep run either way.
void order_sweeps(std::vector<Sweep>& sweeps, const std::optional<Vec3d>& start) {
    const std::size_t m = sweeps.size();
    if (m == 0) return;
    std::vector<std::size_t> seq;
    std::vector<std::uint8_t> flip, done(m, 0);
    Vec3d at = start.value_or(sweeps[0].entry[0]);
    for (std::size_t k = 0; k < m; ++k) {
        std::size_t best = m;
        std::uint8_t best_flip = 0;
        double best_d = 0;
        for (std::size_t i = 0; i < m; ++i) {
            if (done[i]) continue;
            for (std::uint8_t f = 0; f < 2; ++f) {
                const double d = (sweeps[i].entry[f] - at).norm();
                if (best == m || d < best_d) {
                    best = i;
                    best_flip = f;
                    best_d = d;
                }
            }
        }
        done[best] = 1;
        seq.push_back(best);
        flip.push_back(best_flip);
        at = sweeps[best].exit[best_flip];
    }
    // The tour by position: each position's entry and exit, as the tour runs it and turned, and
    // the length of the move leaving it. A 2-opt move then costs two distances, read from
    // contiguous arrays, instead of four through the sweeps; a reversal rewrites the positions it
    // turns. The same sums as distances computed afresh: the same moves, the same plan.
    std::vector<Vec3d> en(m), ex(m), en_turned(m), ex_turned(m);
    for (std::size_t k = 0; k < m; ++k) {
        const Sweep& s = sweeps[seq[k]];
        en[k] = s.entry[flip[k]];
        ex[k] = s.exit[flip[k]];
        en_turned[k] = s.entry[flip[k] ^ 1];
        ex_turned[k] = s.exit[flip[k] ^ 1];
    }
    std::vector<double> leaving(m, 0.0);  // leaving[k]: from position k's exit to k + 1's entry
    auto measure = [&](std::size_t k) {
        if (k + 1 < m) leaving[k] = (en[k + 1] - ex[k]).norm();
    };
    for (std::size_t k = 0; k < m; ++k) measure(k);
    // A pass tests about m^2 / 2 moves, and a cluttered room has thousands of planes (Bobkov's
    // office: 4,455, still improving after 100 passes, which took 10 s). So 2-opt stops once it
    // has tested this many moves (0.1-0.2 s), keeping the best order found so far: every
    // built-in scene's plan (at most a few hundred planes) is unchanged.
    constexpr std::uint64_t kTwoOptBudget = 20'000'000;
    std::uint64_t tested = 0;
    for (int pass = 0; pass < 100 && m > 1 && tested < kTwoOptBudget; ++pass) {
        bool improved = false;
        for (std::size_t i = 0; i < m && tested < kTwoOptBudget; ++i) {
            tested += m - i;
            const bool has_prev = i > 0 || start.has_value();
            const Vec3d prev = i > 0 ? ex[i - 1] : start.value_or(Vec3d::Zero());
            double head = has_prev ? (en[i] - prev).norm() : 0.0;
            for (std::size_t j = i; j < m; ++j) {
                double before = 0, after = 0;
                if (has_prev) {
                    before += head;
                    after += (en_turned[j] - prev).norm();
                }
                if (j + 1 < m) {
                    before += leaving[j];
                    after += (en[j + 1] - ex_turned[i]).norm();
                }
                if (after < before - 1e-9 * (1 + before)) {
                    const auto b = long(i), e = long(j) + 1;
                    std::reverse(seq.begin() + b, seq.begin() + e);
                    std::reverse(flip.begin() + b, flip.begin() + e);
                    for (std::size_t k = i; k <= j; ++k) flip[k] ^= 1;
                    for (std::vector<Vec3d>* v : {&en, &ex, &en_turned, &ex_turned})
                        std::reverse(v->begin() + b, v->begin() + e);
                    for (std::size_t k = i; k <= j; ++k) {
                        std::swap(en[k], en_turned[k]);
                        std::swap(ex[k], ex_turned[k]);
                    }
                    for (std::size_t k = i > 0 ? i - 1 : 0; k <= j; ++k) measure(k);
                    if (has_prev) head = (en[i] - prev).norm();
                    improved = true;
                }
            }
        }
        if (!improved) break;
    }
    std::vector<Sweep> ordered;
    ordered.reserve(m);
    for (std::size_t k = 0; k < m; ++k) {
        ordered.push_back(std::move(sweeps[seq[k]]));
        ordered.back().reversed = flip[k] != 0;
    }
    sweeps = std::move(ordered);
}

}  // namespace

// Refuses a blast radius so small against the planes that the goal lattice alone would have more
// than kMaxGoalCandidates points (a micrometre over a room once ran for minutes, then aborted).
void check_lattice_size(const BoundPlanes& planes, double blast_radius) {
    const double row_step = 1.5 * blast_radius, col_step = std::sqrt(3.0) * blast_radius;
    double candidates = 0, widest = 0;
    for (const BoundPlane& plane : planes.planes) {
        Vec2d lo = Vec2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const PolygonWithHoles& p : plane.polygons)
            for (const Vec2d& q : p.outer) {
                lo = lo.cwiseMin(q);
                hi = hi.cwiseMax(q);
            }
        if (!(lo.x() <= hi.x())) continue;
        candidates += ((hi.x() - lo.x()) / col_step + 3) * ((hi.y() - lo.y()) / row_step + 3);
        widest = std::max(widest, (hi - lo).maxCoeff());
    }
    if (candidates > kMaxGoalCandidates) {
        char figures[96];
        std::snprintf(figures, sizeof figures, "%.4g across: %.3g goal candidates (at most %.3g)",
                      widest, candidates, kMaxGoalCandidates);
        bad({"blast radius ", num(blast_radius), " is too small for planes up to ", figures,
             "; raise the blast radius"});
    }
}

void validate(const CoverageConfig& c) {
    check_length_range("blast radius", c.blast_radius);
    check_length_range("standoff", c.standoff);
    check_length_range("sample spacing", c.sample_spacing);
    if (c.start)
        for (int k = 0; k < 3; ++k) check_length_range("start position", (*c.start)[k]);
    auto length = [](const char* name, double v, bool zero_ok) {
        if (!std::isfinite(v) || v < 0 || (!zero_ok && v == 0))
            bad({name, zero_ok ? " must be >= 0 (0: default), got " : " must be positive, got ",
                 num(v)});
    };
    length("blast radius", c.blast_radius, true);
    length("standoff", c.standoff, false);
    length("sample spacing", c.sample_spacing, true);
    if (!(c.min_angle_deg >= 0 && c.min_angle_deg <= c.max_angle_deg && c.max_angle_deg < 90))
        bad({"angle band must satisfy 0 <= min <= max < 90 degrees, got ", num(c.min_angle_deg),
             ":", num(c.max_angle_deg)});
    if (c.tilt_deg && !(*c.tilt_deg >= c.min_angle_deg && *c.tilt_deg <= c.max_angle_deg))
        bad({"tilt ", num(*c.tilt_deg), " degrees lies outside the angle band ",
             num(c.min_angle_deg), ":", num(c.max_angle_deg)});
    if (c.start && !c.start->allFinite()) bad({"start position must be finite"});
    if (c.blast_radius > 0 && c.sample_spacing > c.blast_radius)
        bad({"sample spacing ", num(c.sample_spacing), " exceeds the blast radius ",
             num(c.blast_radius)});
    if (c.threads < 0) bad({"threads must be >= 0, got ", std::to_string(c.threads)});
}

CoveragePlan plan_coverage(const BoundPlanes& planes, std::span<const Surface> surfaces,
                           const CoverageConfig& config, CoverageMemo* memo) {
    validate(config);
    CoveragePlan plan;
    CoverageConfig& cfg = plan.config;
    cfg = config;
    if (cfg.blast_radius == 0) cfg.blast_radius = planes.config.mu;
    if (!(cfg.blast_radius > 0)) bad({"blast radius must be positive (the planes carry no mu)"});
    if (cfg.sample_spacing == 0) cfg.sample_spacing = cfg.blast_radius / 3;
    if (cfg.sample_spacing > cfg.blast_radius)
        bad({"sample spacing ", num(cfg.sample_spacing), " exceeds the blast radius ",
             num(cfg.blast_radius)});
    // The work grows as (blast radius / spacing)^4 while the plan hardly changes (15041 goals at
    // a third of it, 15380 at a twentieth, on a room); 1 um once ran for minutes.
    if (cfg.sample_spacing < cfg.blast_radius / kMaxSamplesPerBlastRadius)
        bad({"sample spacing ", num(cfg.sample_spacing), " is finer than the blast radius / ",
             num(kMaxSamplesPerBlastRadius), " (",
             num(cfg.blast_radius / kMaxSamplesPerBlastRadius), "): a finer grid only costs time"});
    if (!cfg.tilt_deg) cfg.tilt_deg = cfg.min_angle_deg;
    check_lattice_size(planes, cfg.blast_radius);
    const int threads = resolve_threads(cfg.threads);

    const std::size_t np = planes.planes.size();
    std::vector<PlaneGoals> goals(np);
    const bool recall = memo && memo->blast_radius == cfg.blast_radius &&
                        memo->sample_spacing == cfg.sample_spacing;
    detail::ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t p = 0; p < np; ++p)
        errors.run(p, [&] {
            const PlaneGoals* same =
                recall ? remembered_goals(*memo, planes.planes[p], surfaces) : nullptr;
            goals[p] = same ? *same
                            : cover_plane(planes.planes[p], surfaces, cfg.blast_radius,
                                          cfg.sample_spacing);
        });
    errors.rethrow();

    const double tilt = *cfg.tilt_deg * kDeg;
    std::vector<Sweep> sweeps;
    for (std::size_t p = 0; p < np; ++p) {
        const BoundPlane& bp = planes.planes[p];
        plan.stats.area += bp.area;
        plan.stats.covered_area += bp.area * goals[p].covered_fraction;
        if (goals[p].points.empty()) continue;
        Sweep s = make_sweep(static_cast<std::uint32_t>(p), goals[p]);
        auto tool_at = [&](std::size_t k, double sign) {
            return pose_at(bp.to_world(goals[p].points[s.order[k]]), bp.normal,
                           sign * s.dir[k] * bp.u_axis, tilt, cfg.standoff)
                .tool;
        };
        const std::size_t last = s.order.size() - 1;
        s.entry[0] = tool_at(0, 1);
        s.exit[0] = tool_at(last, 1);
        s.entry[1] = tool_at(last, -1);
        s.exit[1] = tool_at(0, -1);
        sweeps.push_back(std::move(s));
    }
    order_sweeps(sweeps, cfg.start);

    std::size_t goal_count = 0;
    for (const Sweep& s : sweeps) goal_count += s.order.size();
    plan.goals.reserve(goal_count);  // a map's 80k goals, 17 MB: no copies while they are added
    plan.per_plane.reserve(sweeps.size());

    for (const Sweep& s : sweeps) {
        const BoundPlane& bp = planes.planes[s.plane];
        const PlaneGoals& g = goals[s.plane];
        PlaneCoverage pc;
        pc.plane = s.plane;
        pc.goals = static_cast<std::uint32_t>(s.order.size());
        pc.first_goal = static_cast<std::uint32_t>(plan.goals.size());
        pc.area = bp.area;
        pc.covered_fraction = g.covered_fraction;
        plan.per_plane.push_back(pc);
        const std::size_t n = s.order.size();
        for (std::size_t j = 0; j < n; ++j) {
            const std::size_t k = s.reversed ? n - 1 - j : j;
            const std::uint32_t i = s.order[k];
            CoverageGoal goal;
            goal.plane = s.plane;
            goal.row = g.rows[i];
            goal.position = bp.to_world(g.points[i]);
            goal.normal = bp.normal;
            goal.direction = (s.reversed ? -1.0 : 1.0) * s.dir[k] * bp.u_axis;
            const Pose pose = pose_at(goal.position, bp.normal, goal.direction, tilt, cfg.standoff);
            goal.tool_position = pose.tool;
            goal.tool_axis = pose.axis;
            goal.orientation = pose.q;
            goal.tilt_deg =
                std::atan2(pose.axis.cross(-bp.normal).norm(), -pose.axis.dot(bp.normal)) / kDeg;
            goal.from_home = g.from_home[i] != 0;
            goal.transition = j == 0 && !plan.goals.empty();
            plan.goals.push_back(goal);
        }
    }

    CoverageStats& st = plan.stats;
    st.goals = plan.goals.size();
    st.planes = sweeps.size();
    st.transitions = sweeps.empty() ? 0 : sweeps.size() - 1;
    st.coverage = st.area > 0 ? st.covered_area / st.area : 0.0;
    for (std::size_t k = 1; k < plan.goals.size(); ++k) {
        const CoverageGoal &a = plan.goals[k - 1], &b = plan.goals[k];
        const double d = (b.tool_position - a.tool_position).norm();
        st.tool_path_length += d;
        (b.transition ? st.transition_length : st.sweep_length) += d;
        st.goal_path_length += (b.position - a.position).norm();
    }
    if (memo) remember_goals(*memo, planes, surfaces, std::move(goals), cfg);
    return plan;
}

}  // namespace surfgrow
