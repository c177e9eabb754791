#include "surfgrow/planes/bound_planes.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <initializer_list>
#include <numeric>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/parallel_errors.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/length_limits.hpp"
#include "surfgrow/core/moments.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/planes/bound_plane_memo.hpp"
#include "surfgrow/planes/detail/region_fit.hpp"
#include "surfgrow/planes/detail/region_plane.hpp"
#include "surfgrow/planes/patch_adjacency.hpp"
#include "surfgrow/planes/patch_members.hpp"

namespace surfgrow {

namespace {

using detail::add_judge;
using detail::add_normal;
using detail::Fit;
using detail::median_of;
using detail::region_fit;

constexpr double kDeg = M_PI / 180.0;

[[noreturn]] void bad(std::initializer_list<std::string_view> what) {
    throw Error(ErrorCode::kInvalidParameter, cat(what));
}

// Regions of coplanar patches, by index.
struct Regions {
    std::vector<std::int32_t> of_patch;
    std::vector<std::vector<std::uint32_t>> members;
    std::vector<CentredMoments> moments;
    std::vector<Vec3d> judges;  ///< the normals of the patches that span their balls (add_judge)
};

// A region of at most kFragmentPatches patches (a patch on an edge, a noisy patch whose normal
// missed the angle test) whose member points lie, at least kFragmentFit of them, as close to an
// adjacent larger region's plane as that region's own points do (within the offset, or twice
// the region's RMS thickness if larger) joins that region: its points belong to the face,
// and left alone it would punch a hole in the face's boundary. The target planes are fitted
// before any fragment moves, so the outcome does not depend on the order.
constexpr std::size_t kFragmentPatches = 2;
constexpr double kFragmentFit = 0.8;

void absorb_fragments(const PatchMembers& members, const std::vector<std::uint32_t>& adj_off,
                      const std::vector<std::uint32_t>& adj, const BoundPlaneConfig& cfg,
                      const std::vector<CentredMoments>& moments, Regions& regions) {
    std::vector<std::int32_t>& region = regions.of_patch;
    std::vector<std::vector<std::uint32_t>>& region_members = regions.members;
    std::vector<CentredMoments>& region_moments = regions.moments;
    const std::size_t nr = region_members.size();
    std::vector<Plane> planes(nr);
    std::vector<double> tolerance(nr);
    std::vector<std::uint8_t> defined(nr);  // a region whose points define no plane takes none
    for (std::size_t r = 0; r < nr; ++r) {
        const CentredMoments& m = region_moments[r];
        const Fit f = region_fit(m, regions.judges[r]);
        planes[r] = Plane::through(m.mean, f.normal);
        tolerance[r] = std::max(cfg.max_offset, 2 * std::sqrt(f.eigenvalues[0]));
        defined[r] = !f.degenerate;
    }
    std::vector<std::int32_t> target(nr, -1);
    std::vector<std::int32_t> candidates;
    for (std::size_t r = 0; r < nr; ++r) {
        if (region_members[r].size() > kFragmentPatches) continue;
        candidates.clear();
        for (const std::uint32_t p : region_members[r])
            for (std::uint32_t k = adj_off[p]; k < adj_off[p + 1]; ++k) {
                const std::int32_t q = region[adj[k]];
                if (region_members[static_cast<std::size_t>(q)].size() > kFragmentPatches &&
                    defined[static_cast<std::size_t>(q)])
                    candidates.push_back(q);
            }
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        double best = kFragmentFit;
        for (const std::int32_t q : candidates) {
            const Plane& plane = planes[static_cast<std::size_t>(q)];
            std::size_t fit = 0, total = 0;
            for (const std::uint32_t p : region_members[r])
                for (const Vec3f& x : members.points_of(p)) {
                    ++total;
                    fit += std::abs(plane.signed_distance(x.cast<double>())) <=
                           tolerance[static_cast<std::size_t>(q)];
                }
            const double share = total ? double(fit) / double(total) : 0.0;
            if (share >= best) {  // ties: the earlier (larger-seeded) region
                if (share > best || target[r] < 0) target[r] = q;
                best = share;
            }
        }
    }
    for (std::size_t r = 0; r < nr; ++r) {
        if (target[r] < 0) continue;
        const auto q = static_cast<std::size_t>(target[r]);
        for (const std::uint32_t p : region_members[r]) {
            region[p] = target[r];
            region_members[q].push_back(p);
            region_moments[q].merge(moments[p]);
        }
        add_normal(regions.judges[q], regions.judges[r], 1.0);
        region_members[r].clear();
        region_moments[r] = CentredMoments{};
        regions.judges[r] = Vec3d::Zero();
    }
}

// How much worse than its own plane the pooled plane fits a region's points: the RMS of the
// extra distance, from the offset of the region's centroid and the tilt across its extent. Two
// parallel strips a step apart are always passed through by some tilted plane at both centroids;
// the tilt shows here, over each strip's length.
double misfit(const CentredMoments& m, const Fit& own, const Fit& pooled, const Vec3d& at) {
    return std::sqrt(std::max(m.mean_square_distance(pooled.normal, at) - own.eigenvalues[0], 0.0));
}

// The step between two regions that their pooled plane hides by leaning: pooled pieces of one
// plane give a normal on the arc between theirs; two parallel faces a step apart, side by side,
// give a plane through both centroids, leaning off that arc by about the step over their
// distance. The lean's share along the line between the centroids, times its length.
double hidden_step(const Vec3d& na, const Vec3d& nb_in, const Vec3d& np_in, const Vec3d& a,
                   const Vec3d& b) {
    const Vec3d nb = nb_in.dot(na) < 0 ? Vec3d(-nb_in) : nb_in;
    const Vec3d np = np_in.dot(na) < 0 ? Vec3d(-np_in) : np_in;
    Vec3d on_arc = na;  // the arc's point nearest the pooled normal
    const Vec3d axis = na.cross(nb);
    if (axis.norm() > 1e-12) {
        const Vec3d c = axis.normalized();
        const Vec3d in_plane = np - np.dot(c) * c;  // none only 90 degrees from both
        const Vec3d g = in_plane.norm() > 1e-12 ? Vec3d(in_plane.normalized()) : na;
        if (na.cross(g).dot(c) >= 0 && g.cross(nb).dot(c) >= 0)
            on_arc = g;
        else if (np.dot(nb) > np.dot(na))
            on_arc = nb;
    }
    return std::abs((np - on_arc).dot(b - a));
}

// Coplanar regions whose patches come within max_gap of each other (a face seen in bands between
// occlusion shadows, a plate behind a stiffener) are one face: merged when both planes and their
// pooled fit agree in angle, and the pooled plane fits each within the offset (misfit). Pairs
// are tried in region order; pooled moments keep chains of merges from drifting.
void bridge_gaps(std::span<const Surface> surfaces, const std::vector<std::uint8_t>& used,
                 const BoundPlaneConfig& cfg, Regions& regions, int threads) {
    const std::vector<std::int32_t>& region = regions.of_patch;
    std::vector<std::vector<std::uint32_t>>& region_members = regions.members;
    std::vector<CentredMoments>& region_moments = regions.moments;
    const std::size_t nr = region_members.size();
    if (cfg.max_gap <= 0 || nr < 2) return;
    std::vector<Vec3f> homes(surfaces.size());
    std::vector<double> radii;
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        homes[s] = surfaces[s].home.cast<float>();
        if (used[s]) radii.push_back(surfaces[s].radius);
    }
    // Candidate region pairs, in parallel over the patches (sorted and unique in the end, so the
    // same for any thread count). Patches a, b qualify when |home b - home a| - r_a - r_b is at
    // most the gap, so within gap + 2 max(r_a, r_b): each pair is found from its larger patch,
    // whose search then need not allow for the largest radius of all. Cubes suit the common one.
    const CubeIndex index(
        homes, (cfg.max_gap + 2 * median_of(std::move(radii))) * kSearchSideMargin, used, 1);
    const auto original = index.original_indices();
    // Regions in the index's order, -1 for regions absorbed as fragments: most homes within reach
    // are of the patch's own region, and this skips them before any distance.
    constexpr std::uint32_t kNone = ~std::uint32_t{0};
    std::vector<std::uint32_t> region_at(index.size());
    for (std::size_t j = 0; j < index.size(); ++j) {
        const auto r = static_cast<std::uint32_t>(region[original[j]]);
        region_at[j] = region_members[r].empty() ? kNone : r;
    }
    // Homes of one cube are mostly of one region: the end of each run of equal regions lets a
    // search skip the patch's own region (and absorbed ones) a run at a time.
    std::vector<std::uint32_t> run_end(index.size());
    for (std::size_t j = index.size(); j-- > 0;)
        run_end[j] = j + 1 < index.size() && region_at[j + 1] == region_at[j]
                         ? run_end[j + 1]
                         : static_cast<std::uint32_t>(j + 1);
    std::vector<std::vector<std::uint64_t>> found(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
    {
        // Filled here and moved: two threads' vectors side by side would share a cache line.
        std::vector<std::uint64_t> out;
        // The patch that last paired with each region: later homes of that region are skipped.
        std::vector<std::size_t> paired_by(nr, surfaces.size());
#pragma omp for schedule(dynamic, 256)
        for (std::size_t p = 0; p < surfaces.size(); ++p) {
            if (!used[p]) continue;
            const Surface& a = surfaces[p];
            const auto ra = static_cast<std::uint32_t>(region[p]);
            if (region_members[ra].empty()) continue;
            for_each_home_near(
                index, a.home, cfg.max_gap + 2 * a.radius,
                [&](std::uint32_t j) {
                    const std::uint32_t r = region_at[j];
                    return r != ra && r != kNone && paired_by[r] != p ? j : run_end[j];
                },
                [&](std::uint32_t j) {
                    const Surface& b = surfaces[original[j]];
                    if (b.radius > a.radius ||
                        (b.home - a.home).norm() - a.radius - b.radius > cfg.max_gap)
                        return;
                    paired_by[region_at[j]] = p;
                    out.push_back(pair_key(ra, region_at[j]));
                });
        }
        found[static_cast<std::size_t>(omp_get_thread_num())] = std::move(out);
    }
    const std::vector<std::uint64_t> pairs = merged_unique({&found});
    std::vector<std::uint32_t> parent(nr);
    std::iota(parent.begin(), parent.end(), 0u);
    auto root = [&](std::uint32_t r) {
        while (parent[r] != r) r = parent[r] = parent[parent[r]];
        return r;
    };
    const double cos_max = std::cos(cfg.max_angle_deg * kDeg);
    auto parallel = [&](const Vec3d& x, const Vec3d& y) { return std::abs(x.dot(y)) >= cos_max; };
    for (const std::uint64_t key : pairs) {
        const std::uint32_t a = root(pair_of_key(key).first);
        const std::uint32_t b = root(pair_of_key(key).second);
        if (a == b) continue;
        const CentredMoments &ma = region_moments[a], &mb = region_moments[b];
        CentredMoments pooled = ma;
        pooled.merge(mb);
        Vec3d judge = regions.judges[a];
        add_normal(judge, regions.judges[b], 1.0);
        const Fit fa = region_fit(ma, regions.judges[a]), fb = region_fit(mb, regions.judges[b]),
                  fp = region_fit(pooled, judge);
        if (fa.degenerate || fb.degenerate || fp.degenerate) continue;
        if (!parallel(fa.normal, fb.normal) || !parallel(fa.normal, fp.normal) ||
            !parallel(fb.normal, fp.normal))
            continue;
        if (misfit(ma, fa, fp, pooled.mean) > cfg.max_offset ||
            misfit(mb, fb, fp, pooled.mean) > cfg.max_offset)
            continue;
        if (hidden_step(fa.normal, fb.normal, fp.normal, ma.mean, mb.mean) > 2 * cfg.max_offset)
            continue;
        const std::uint32_t keep = std::min(a, b), gone = std::max(a, b);
        parent[gone] = keep;
        region_moments[keep] = pooled;
        region_moments[gone] = CentredMoments{};
        regions.judges[keep] = judge;
        regions.judges[gone] = Vec3d::Zero();
        auto& list = region_members[keep];
        list.insert(list.end(), region_members[gone].begin(), region_members[gone].end());
        region_members[gone].clear();
    }
}

// ---- The stages of compute_bound_planes, in the order it runs them.

// Throws Error(kInvalidParameter) for labels or surfaces that are not a grow result of `cloud`.
void check_grow_result(const CloudView& cloud, std::span<const Surface> surfaces,
                       std::span<const std::int32_t> labels) {
    if (labels.size() != cloud.size())
        bad({"bound planes: ", std::to_string(labels.size()), " labels for ",
             std::to_string(cloud.size()), " points"});
    for (std::size_t i = 0; i < labels.size(); ++i)
        if (labels[i] < -1 ||
            (labels[i] >= 0 && static_cast<std::size_t>(labels[i]) >= surfaces.size()))
            bad({"bound planes: point ", std::to_string(i), " has label ",
                 std::to_string(labels[i]), " but there are ", std::to_string(surfaces.size()),
                 " surfaces"});
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        const Surface& f = surfaces[s];
        if (!f.normal.allFinite() || std::abs(f.normal.norm() - 1) > 1e-6 ||
            !f.centroid.allFinite() || !f.home.allFinite() || !(f.radius > 0))
            bad({"bound planes: surface ", std::to_string(s),
                 " has a non-unit normal, a non-finite position or no radius"});
    }
}

// The centred moments of each patch's member points from their sums about its home point;
// `used` marks the patches with members. Returns the median patch thickness sqrt(lambda_min):
// the cloud's noise.
double patch_moments(std::span<const Surface> surfaces, const PatchMembers& members,
                     std::span<const Moments> about_home, std::vector<CentredMoments>& moments,
                     std::vector<std::uint8_t>& used) {
    std::vector<double> thickness;
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        if (members.of(s).empty()) continue;
        used[s] = 1;
        moments[s] = CentredMoments::of(about_home[s], surfaces[s].home);
        thickness.push_back(std::sqrt(std::max(surfaces[s].eigenvalues[0], 0.0)));
    }
    return median_of(std::move(thickness));
}

// The defaults of a configuration's lengths, from mu and the measured noise.
void resolve_defaults(BoundPlaneConfig& cfg, double noise) {
    if (cfg.max_offset == 0) cfg.max_offset = std::clamp(3 * noise, cfg.mu / 4, cfg.mu / 2);
    if (cfg.adjacency == 0) cfg.adjacency = cfg.mu / 2;
    if (cfg.max_gap == 0) cfg.max_gap = 5 * cfg.mu;
    if (cfg.resolution == 0) cfg.resolution = cfg.mu / 2;
    if (cfg.simplify_tolerance == 0) cfg.simplify_tolerance = cfg.resolution;
}

// Which patches touch which, as CSR from the pairs' keys (pair_key, sorted): the neighbours of s
// are adj[off[s], off[s + 1]), ascending.
struct PatchGraph {
    std::vector<std::uint32_t> off;
    std::vector<std::uint32_t> adj;
};

PatchGraph patch_graph(std::span<const std::uint64_t> pairs, std::size_t ns) {
    PatchGraph g;
    std::vector<std::uint32_t>& adj_off = g.off;
    std::vector<std::uint32_t>& adj = g.adj;
    adj_off.assign(ns + 1, 0);
    for (const std::uint64_t key : pairs) {
        const auto [a, b] = pair_of_key(key);
        ++adj_off[a + 1];
        ++adj_off[b + 1];
    }
    for (std::size_t s = 0; s < ns; ++s) adj_off[s + 1] += adj_off[s];
    adj.resize(adj_off[ns]);
    std::vector<std::uint32_t> fill(adj_off.begin(), adj_off.end() - 1);
    for (const std::uint64_t key : pairs) {  // sorted, so each list comes out ascending
        const auto [a, b] = pair_of_key(key);
        adj[fill[a]++] = b;
        adj[fill[b]++] = a;
    }
    for (std::size_t s = 0; s < ns; ++s)
        std::sort(adj.begin() + adj_off[s], adj.begin() + adj_off[s + 1]);
    return g;
}

// Regions of coplanar patches: each patch's region (-1: none), each region's patches and pooled
// moments.

// Removes the regions merged into others (members emptied); of_patch is not used after.
void drop_emptied(Regions& regions) {
    std::size_t kept = 0;
    for (std::size_t r = 0; r < regions.members.size(); ++r) {
        if (regions.members[r].empty()) continue;
        if (kept != r) {
            regions.members[kept] = std::move(regions.members[r]);
            regions.moments[kept] = regions.moments[r];
            regions.judges[kept] = regions.judges[r];
        }
        ++kept;
    }
    regions.members.resize(kept);
    regions.moments.resize(kept);
    regions.judges.resize(kept);
}

// Region growing over the patch graph, seeds by decreasing member count: a neighbour joins when
// it is coplanar with the patch that reached it and with the region's pooled plane so far.
Regions grow_regions(std::span<const Surface> surfaces, const PatchMembers& members,
                     const std::vector<CentredMoments>& moments,
                     const std::vector<std::uint8_t>& used, const PatchGraph& graph,
                     const BoundPlaneConfig& cfg) {
    const std::size_t ns = surfaces.size();
    const std::vector<std::uint32_t>& adj_off = graph.off;
    const std::vector<std::uint32_t>& adj = graph.adj;
    const double cos_max = std::cos(cfg.max_angle_deg * kDeg);
    const double off = cfg.max_offset;
    auto parallel = [&](const Vec3d& a, const Vec3d& b) { return std::abs(a.dot(b)) >= cos_max; };
    auto coplanar = [&](const Surface& p, const Surface& q) {
        return parallel(p.normal, q.normal) &&
               std::abs(q.plane().signed_distance(p.centroid)) <= off &&
               std::abs(p.plane().signed_distance(q.centroid)) <= off;
    };
    Regions regions;
    std::vector<std::int32_t>& region = regions.of_patch;
    std::vector<std::vector<std::uint32_t>>& region_members = regions.members;
    std::vector<CentredMoments>& region_moments = regions.moments;
    region.assign(ns, -1);
    std::vector<std::uint32_t> seeds;
    for (std::uint32_t s = 0; s < ns; ++s)
        if (used[s]) seeds.push_back(s);
    std::stable_sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) {
        return members.of(a).size() > members.of(b).size();
    });
    std::deque<std::uint32_t> queue;
    for (const std::uint32_t seed : seeds) {
        if (region[seed] >= 0) continue;
        const auto r = static_cast<std::int32_t>(region_members.size());
        std::vector<std::uint32_t> list{seed};
        CentredMoments pooled = moments[seed];
        Vec3d weighted = Vec3d::Zero();  // the normal while the points cannot define one
        Vec3d judge = Vec3d::Zero();
        add_normal(weighted, surfaces[seed].normal, pooled.n);
        add_judge(judge, surfaces[seed], pooled.n);
        bool defined = true;  // whether the points define the region's plane (region_fit)
        auto region_normal = [&] {
            const Fit f = region_fit(pooled, judge);
            defined = !f.degenerate;
            return f.degenerate ? Vec3d(weighted.normalized()) : f.normal;
        };
        Vec3d rn = region_normal();
        region[seed] = r;
        queue.assign(1, seed);
        while (!queue.empty()) {
            const std::uint32_t q = queue.front();
            queue.pop_front();
            for (std::uint32_t k = adj_off[q]; k < adj_off[q + 1]; ++k) {
                const std::uint32_t p = adj[k];
                if (region[p] >= 0) continue;
                const Surface& sp = surfaces[p];
                // A region whose points define no plane is not held to its mean's offset: along
                // its normal they spread by noise as deep as the strip (27 mm on a stiffener's
                // end). Patch to patch the offset still holds (coplanar).
                if (!coplanar(sp, surfaces[q]) || !parallel(sp.normal, rn) ||
                    (defined && std::abs(rn.dot(sp.centroid - pooled.mean)) > off))
                    continue;
                region[p] = r;
                list.push_back(p);
                pooled.merge(moments[p]);
                add_normal(weighted, sp.normal, moments[p].n);
                add_judge(judge, sp, moments[p].n);
                rn = region_normal();
                queue.push_back(p);
            }
        }
        region_members.push_back(std::move(list));
        region_moments.push_back(pooled);
        regions.judges.push_back(judge);
    }
    return regions;
}

// The planes in publishing order, largest first (ties by smallest member id: every plane has
// members, all distinct), with each patch's plane and the totals.
void publish_planes(std::vector<BoundPlane>& planes, BoundPlanes& out) {
    const std::size_t nr = planes.size();
    std::vector<std::size_t> order(nr);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (planes[a].point_count != planes[b].point_count)
            return planes[a].point_count > planes[b].point_count;
        return planes[a].patches[0] < planes[b].patches[0];
    });
    out.planes.reserve(nr);
    for (const std::size_t r : order) {
        const auto id = static_cast<std::int32_t>(out.planes.size());
        for (const std::uint32_t s : planes[r].patches) out.plane_of_patch[s] = id;
        out.stats.patches_merged += planes[r].patches.size();
        out.stats.points += planes[r].point_count;
        out.stats.degenerate += planes[r].degenerate ? 1 : 0;
        out.stats.area += planes[r].area;
        out.planes.push_back(std::move(planes[r]));
    }
}

}  // namespace

void validate(const BoundPlaneConfig& c) {
    const std::pair<const char*, double> all_lengths[] = {
        {"mu", c.mu},
        {"plane offset", c.max_offset},
        {"adjacency distance", c.adjacency},
        {"max gap", c.max_gap},
        {"boundary resolution", c.resolution},
        {"closing radius", c.closing_radius},
        {"simplify tolerance", c.simplify_tolerance}};
    for (const auto& [name, v] : all_lengths) check_length_range(name, v);
    if (!(c.mu > 0) || !std::isfinite(c.mu)) bad({"mu must be positive, got ", num(c.mu)});
    if (!(c.max_angle_deg > 0 && c.max_angle_deg < 90))
        bad({"plane angle must be between 0 and 90 degrees, got ", num(c.max_angle_deg)});
    const std::pair<const char*, double> lengths[] = {{"plane offset", c.max_offset},
                                                      {"adjacency distance", c.adjacency},
                                                      {"boundary resolution", c.resolution},
                                                      {"closing radius", c.closing_radius},
                                                      {"simplify tolerance", c.simplify_tolerance}};
    for (const auto& [name, v] : lengths)
        if (!(v >= 0) || !std::isfinite(v)) bad({name, " must be >= 0 (0: default), got ", num(v)});
    if (!std::isfinite(c.max_gap)) bad({"max gap must be finite, got ", num(c.max_gap)});
    if (c.resolution > 0 && c.resolution < c.mu * 1e-3)
        bad({"boundary resolution ", num(c.resolution), " is below mu / 1000"});
    // Every member point is paired with all others within the adjacency: at 0.8 m on a room at
    // mu = 12 mm that took 8 GB within a minute. Patches that touch lie within mu of each other.
    if (c.adjacency > 0 && c.adjacency < c.mu * 1e-3)  // as the resolution: cubes beyond count
        bad({"adjacency distance ", num(c.adjacency), " is below mu / 1000"});
    if (c.adjacency > kMaxAdjacencyPerMu * c.mu)
        bad({"adjacency distance ", num(c.adjacency), " is more than ", num(kMaxAdjacencyPerMu),
             " mu (", num(kMaxAdjacencyPerMu * c.mu),
             "): patches are neighbours when their points nearly touch"});
    if (c.threads < 0) bad({"threads must be >= 0, got ", std::to_string(c.threads)});
}

std::vector<std::int32_t> plane_labels(const BoundPlanes& planes,
                                       std::span<const std::int32_t> labels) {
    std::vector<std::int32_t> out(labels.size(), -1);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        const std::int32_t l = labels[i];
        if (l >= 0 && static_cast<std::size_t>(l) < planes.plane_of_patch.size())
            out[i] = planes.plane_of_patch[static_cast<std::size_t>(l)];
    }
    return out;
}

BoundPlanes compute_bound_planes(const CloudView& cloud, std::span<const Surface> surfaces,
                                 std::span<const std::int32_t> labels,
                                 const BoundPlaneConfig& config, BoundPlaneMemo* memo) {
    validate(config);
    check_grow_result(cloud, surfaces, labels);
    BoundPlanes out;
    BoundPlaneConfig& cfg = out.config;
    cfg = config;
    const int threads = resolve_threads(cfg.threads);
    const std::size_t ns = surfaces.size();
    out.plane_of_patch.assign(ns, -1);
    out.stats.patches = ns;

    // Member points (the memo's lists extended by the new points) and their moments per patch
    // (from the memo's sums on, where it has them); the defaults that depend on the noise.
    PatchMembers members = memo ? patch_members(*memo, cloud.points, labels, ns, threads)
                                : collect_patch_members(cloud.points, labels, ns, threads);
    const BoundPlaneMemo none;
    const BoundPlaneMemo& recall = memo ? *memo : none;
    const KnownMembers known = known_members(recall, members, surfaces);
    std::vector<Moments> about_home;
    std::vector<Aabb> boxes;
    patch_sums(recall, known, members, surfaces, about_home, boxes, threads);
    std::vector<CentredMoments> moments(ns);
    std::vector<std::uint8_t> used(ns, 0);
    out.stats.noise = patch_moments(surfaces, members, about_home, moments, used);
    resolve_defaults(cfg, out.stats.noise);

    // Patch graph (sought only where patches changed since the memo), regions of coplanar
    // patches, fragments absorbed and gaps bridged.
    std::vector<std::uint8_t> changed(ns, 1);
    if (known.valid)
        for (std::size_t s = 0; s < ns; ++s) changed[s] = known.count[s] != members.of(s).size();
    const bool same_reach = known.valid && recall.reach == cfg.adjacency;
    std::vector<std::uint64_t> keys = adjacent_patch_keys(
        members, surfaces, boxes, same_reach ? changed : std::vector<std::uint8_t>(ns, 1),
        same_reach ? std::span<const std::uint64_t>(recall.pairs)
                   : std::span<const std::uint64_t>{},
        cfg.adjacency, threads);
    const auto remember_the_patches = [&] {
        remember_patches(*memo, members, surfaces, std::move(about_home), std::move(boxes),
                         cfg.adjacency, std::move(keys));
    };
    if (ns == 0 || members.index.empty()) {
        if (memo) {
            remember_the_patches();
            remember_planes(*memo, ns, {}, {}, {}, {}, cfg);
        }
        return out;
    }
    out.stats.adjacent_pairs = keys.size();
    const PatchGraph graph = patch_graph(keys, ns);
    Regions regions = grow_regions(surfaces, members, moments, used, graph, cfg);
    absorb_fragments(members, graph.off, graph.adj, cfg, moments, regions);
    bridge_gaps(surfaces, used, cfg, regions, threads);
    drop_emptied(regions);
    for (std::vector<std::uint32_t>& list : regions.members) std::sort(list.begin(), list.end());

    // Each region's plane, frame and boundary: the memo's where it fitted the same region,
    // extended where the region only gained points since (a map), else fitted; independent, so
    // in parallel.
    const std::size_t nr = regions.members.size();
    std::vector<BoundPlane> planes(nr);
    std::vector<RegionState> states(memo ? nr : 0);
    std::vector<const FittedRegion*> kept(nr, nullptr);  // the memo's region, where the same
    detail::ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t r = 0; r < nr; ++r)
        errors.run(r, [&] {
            const std::vector<std::uint32_t>& list = regions.members[r];
            if (const FittedRegion* same = remembered_plane(
                    recall, list, changed, regions.moments[r], regions.judges[r], cfg)) {
                planes[r] = same->plane;
                kept[r] = same;  // its state moves over below
                return;
            }
            const detail::RegionInput in{surfaces,           members,          moments, boxes, list,
                                         regions.moments[r], regions.judges[r]};
            const FittedRegion* was =
                memo && known.valid ? remembered_region(recall, list, cfg) : nullptr;
            planes[r] =
                detail::region_plane(in, was, known.count, cfg, memo ? &states[r] : nullptr);
        });
    errors.rethrow();
    if (memo) {
        // The memo's regions are replaced next: an unchanged region's cell counts move over.
        for (std::size_t r = 0; r < nr; ++r)
            if (kept[r])
                states[r] = std::move(
                    memo->regions[static_cast<std::size_t>(kept[r] - memo->regions.data())].state);
        remember_the_patches();
        remember_planes(*memo, ns, regions.moments, regions.judges, planes, std::move(states), cfg);
        memo->members = std::move(members);
        memo->member_points = labels.size();
    }
    publish_planes(planes, out);
    return out;
}

}  // namespace surfgrow
