#include "surfgrow/planes/patch_adjacency.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace surfgrow {

std::vector<std::uint64_t> merged_unique(
    std::initializer_list<const std::vector<std::vector<std::uint64_t>>*> sources) {
    std::vector<std::uint64_t> all;
    for (const auto* parts : sources)
        for (const auto& v : *parts) all.insert(all.end(), v.begin(), v.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
}

namespace {

// Searching from each changed patch beats sweeping every box when fewer than one in this many
// patches changed.
constexpr std::size_t kFewChanged = 4;

// Boxes are Aabbs in double: exact bounds of float points.
bool near_on_axis(const Aabb& a, const Aabb& b, int axis, double pad) {
    return b.min[axis] - a.max[axis] <= pad && a.min[axis] - b.max[axis] <= pad;
}

// What a pair test may reuse between calls on one thread.
struct Scratch {
    std::vector<Vec3d> near_a, near_b;
};

// Each used box's centre (float, for an index) and largest half extent; `halves` lists the used
// boxes' half extents.
struct BoxCentres {
    std::vector<Vec3f> centre;
    std::vector<double> half, halves;
};
BoxCentres box_centres(const std::vector<Aabb>& box, const std::vector<std::uint8_t>& use) {
    const std::size_t n = box.size();
    BoxCentres c{std::vector<Vec3f>(n, Vec3f::Zero()), std::vector<double>(n, 0.0), {}};
    for (std::size_t s = 0; s < n; ++s) {
        if (!use[s]) continue;
        c.centre[s] = ((box[s].min + box[s].max) / 2).cast<float>();
        c.half[s] = box[s].size().maxCoeff() / 2;
        c.halves.push_back(c.half[s]);
    }
    return c;
}

// The keys of the pairs of boxes among those `use` marks that lie within `pad` of each other on
// every axis and that `touch(a, b, scratch)` accepts, one list per thread. Such boxes' centres
// are within 2 e + pad of each other on every axis, e the larger box's largest half extent: so
// each pair is sought from its larger box, over an index of the centres whose cubes suit the
// common size. A margin keeps the search from deciding a tie; the box test and `touch` decide.
template <class Touch>
std::vector<std::vector<std::uint64_t>> near_box_pairs(const std::vector<Aabb>& box,
                                                       const std::vector<std::uint8_t>& use,
                                                       double pad, int threads, Touch&& touch) {
    BoxCentres boxes = box_centres(box, use);
    const std::vector<Vec3f>& centre = boxes.centre;
    const std::vector<double>& half = boxes.half;
    std::vector<double>& halves = boxes.halves;
    std::vector<std::vector<std::uint64_t>> found(static_cast<std::size_t>(threads));
    if (halves.empty()) return found;
    std::nth_element(halves.begin(), halves.begin() + halves.size() / 2, halves.end());
    // The median box's search then stays within one cube around its own (kSearchSideMargin).
    double side = (2 * halves[halves.size() / 2] + pad) * kSearchSideMargin;
    if (!(side > 0)) side = 1;  // boxes that are points, touching only when they coincide
    const CubeIndex index(centre, side, use, 1);
    const auto original = index.original_indices();
    pad = pad * (1 + 1e-9) + side * 1e-12;
    const double slack = float_rounding_slack(index);  // the centres are floats
    // Box by box in the index's order, a block of cubes at a time: most searches reach one cube
    // around their own, whose 9 column runs one sweep lists for the whole block (a search of its
    // own costs 18 galloping lookups).
    const std::size_t cubes = index.cube_count();
    constexpr std::size_t kBlock = 256;
#pragma omp parallel num_threads(threads)
    {
        // Filled here and moved: two threads' vectors side by side would share a cache line.
        std::vector<std::uint64_t> out;
        Scratch scratch;
        std::vector<CubeIndex::Range> table;
#pragma omp for schedule(dynamic, 1)
        for (std::size_t first = 0; first < cubes; first += kBlock) {
            const std::size_t last = std::min(cubes, first + kBlock);
            index.neighbour_table(first, last, table);
            for (std::size_t c = first; c < last; ++c)
                for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
                    const std::uint32_t a = original[i];
                    const double reach = (2 * half[a] + pad) * (1 + 1e-9) + slack;
                    const auto visit = [&](const CubeIndex::Range& run) {
                        for (std::uint32_t j = run.begin; j < run.end; ++j) {
                            const std::uint32_t b = original[j];
                            // Each pair once: from the larger box, or the lower id of equal ones.
                            if (half[b] > half[a] || (half[b] == half[a] && b <= a)) continue;
                            if (near_on_axis(box[a], box[b], 0, pad) &&
                                near_on_axis(box[a], box[b], 1, pad) &&
                                near_on_axis(box[a], box[b], 2, pad) && touch(a, b, scratch))
                                out.push_back(pair_key(a, b));
                        }
                    };
                    const double ring = search_ring(index, reach);
                    if (ring == 1 && !search_spans_index(index, ring)) {
                        for (std::size_t k = 0; k < 9; ++k) visit(table[9 * (c - first) + k]);
                    } else {
                        for_each_run_near(index, index.to_local(centre[a].cast<double>()), reach,
                                          visit);
                    }
                }
        }
        found[static_cast<std::size_t>(omp_get_thread_num())] = std::move(out);
    }
    return found;
}

// The pairs of near_box_pairs that hold a box listed in `from` (each box at most once), one
// list per thread, at a cost in proportion to the list rather than to all boxes: each listed box
// searches every class of boxes. A class holds the boxes whose largest half extent lies within
// a power of two above the median's, indexed with cubes suited to its largest box, so that a
// search reaches about one cube around its own in the classes of its size and above. Pairs of
// two listed boxes are found twice; the caller's merge keeps one.
template <class Touch>
std::vector<std::vector<std::uint64_t>> box_pairs_of(const std::vector<Aabb>& box,
                                                     const std::vector<std::uint8_t>& use,
                                                     std::span<const std::uint32_t> from,
                                                     double pad, int threads, Touch&& touch) {
    const std::size_t n = box.size();
    std::vector<std::vector<std::uint64_t>> found(static_cast<std::size_t>(threads));
    BoxCentres boxes = box_centres(box, use);
    const std::vector<Vec3f>& centre = boxes.centre;
    const std::vector<double>& half = boxes.half;
    std::vector<double>& halves = boxes.halves;
    if (halves.empty() || from.empty()) return found;
    std::nth_element(halves.begin(), halves.begin() + halves.size() / 2, halves.end());
    const double largest = *std::max_element(halves.begin(), halves.end());
    const double unit = std::max({halves[halves.size() / 2], largest * 1e-6, 1e-30});
    const auto class_of = [&](double h) {
        return h <= unit ? 0 : static_cast<int>(std::ceil(std::log2(h / unit)));
    };
    const auto classes = static_cast<std::size_t>(class_of(largest) + 1);
    std::vector<std::vector<std::uint8_t>> in(classes, std::vector<std::uint8_t>(n, 0));
    std::vector<double> widest(classes, -1.0);
    for (std::size_t s = 0; s < n; ++s)
        if (use[s]) {
            const auto c = static_cast<std::size_t>(class_of(half[s]));
            in[c][s] = 1;
            widest[c] = std::max(widest[c], half[s]);
        }
    struct Class {
        CubeIndex index;
        double widest;
        double slack;
    };
    std::vector<Class> indexed;
    double margin = 0;  // as near_box_pairs: a tie is not left to rounding
    for (std::size_t c = 0; c < classes; ++c) {
        if (widest[c] < 0) continue;
        double side = (2 * widest[c] + pad) * kSearchSideMargin;
        if (!(side > 0)) side = 1;
        CubeIndex index(centre, side, in[c], 1);
        const double slack = float_rounding_slack(index);
        indexed.push_back({std::move(index), widest[c], slack});
        margin = std::max(margin, side * 1e-12);
    }
    pad = pad * (1 + 1e-9) + margin;
    const auto count = static_cast<std::ptrdiff_t>(from.size());
#pragma omp parallel num_threads(threads)
    {
        std::vector<std::uint64_t> out;
        Scratch scratch;
#pragma omp for schedule(dynamic, 64)
        for (std::ptrdiff_t k = 0; k < count; ++k) {
            const std::uint32_t a = from[static_cast<std::size_t>(k)];
            if (!use[a]) continue;
            for (const Class& c : indexed) {
                const auto original = c.index.original_indices();
                const double reach = (half[a] + c.widest + pad) * (1 + 1e-9) + c.slack;
                for_each_run_near(c.index, c.index.to_local(centre[a].cast<double>()), reach,
                                  [&](const CubeIndex::Range& run) {
                                      for (std::uint32_t j = run.begin; j < run.end; ++j) {
                                          const std::uint32_t b = original[j];
                                          if (b != a && near_on_axis(box[a], box[b], 0, pad) &&
                                              near_on_axis(box[a], box[b], 1, pad) &&
                                              near_on_axis(box[a], box[b], 2, pad) &&
                                              touch(a, b, scratch))
                                              out.push_back(pair_key(a, b));
                                      }
                                  });
            }
        }
        found[static_cast<std::size_t>(omp_get_thread_num())] = std::move(out);
    }
    return found;
}

// The points among `members` within `pad` of box `other` on every axis, into `out`.
void members_near(std::span<const Vec3f> members, const Aabb& other, double pad,
                  std::vector<Vec3d>& out) {
    out.clear();
    const Aabb grown{other.min.array() - pad, other.max.array() + pad};
    for (const Vec3f& x : members) {
        const Vec3d p = x.cast<double>();
        if (grown.contains(p)) out.push_back(p);
    }
}

// Whether a point of `a` lies within `reach` of a point of `b`. Two large interlocking patches
// (both faces of a thin plate) would cost n m pairs: there `b` is sorted on x and searched.
bool any_within(std::vector<Vec3d>& a, std::vector<Vec3d>& b, double reach) {
    const double r2 = reach * reach;
    if (a.size() * b.size() <= 256) {
        for (const Vec3d& p : a)
            for (const Vec3d& q : b)
                if ((p - q).squaredNorm() <= r2) return true;
        return false;
    }
    if (b.size() < a.size()) std::swap(a, b);
    std::sort(b.begin(), b.end(), [](const Vec3d& p, const Vec3d& q) { return p.x() < q.x(); });
    for (const Vec3d& p : a) {
        auto q = std::lower_bound(b.begin(), b.end(), p.x() - reach,
                                  [](const Vec3d& v, double x) { return v.x() < x; });
        for (; q != b.end() && q->x() <= p.x() + reach; ++q)
            if ((p - *q).squaredNorm() <= r2) return true;
    }
    return false;
}

}  // namespace

// Adjacency of patches: member points within `reach` of each other, or home points within the
// sum of the radii. Members can only touch where their patches' boxes lie within `reach`, homes
// only where the boxes of their balls meet: a sweep over the boxes finds those pairs (a few per
// patch), and only then are members near the other's box compared, where a patch of the pair
// changed. Sorted, unique keys; the final sort makes the result independent of the thread count.
std::vector<std::uint64_t> adjacent_patch_keys(const PatchMembers& members,
                                               std::span<const Surface> surfaces,
                                               const std::vector<Aabb>& boxes,
                                               std::span<const std::uint8_t> changed,
                                               std::span<const std::uint64_t> known, double reach,
                                               int threads) {
    const std::size_t ns = surfaces.size();
    std::vector<Aabb> ball(ns);
    std::vector<std::uint8_t> with_members(ns, 0);
    for (std::size_t s = 0; s < ns; ++s) {
        if (members.of(s).empty()) continue;
        with_members[s] = 1;
        ball[s] = {surfaces[s].home.array() - surfaces[s].radius,
                   surfaces[s].home.array() + surfaces[s].radius};
    }
    const auto homes_within_radii = [&](std::uint32_t a, std::uint32_t b) {
        return (surfaces[b].home - surfaces[a].home).norm() <=
               surfaces[a].radius + surfaces[b].radius;
    };
    const auto near_homes = [&](std::uint32_t a, std::uint32_t b, Scratch&) {
        return (changed[a] || changed[b]) && homes_within_radii(a, b);
    };
    const auto members_touch = [&](std::uint32_t a, std::uint32_t b, Scratch& scratch) {
        if (!(changed[a] || changed[b])) return false;
        if (homes_within_radii(a, b)) return false;  // the other rule has it
        members_near(members.points_of(a), boxes[b], reach, scratch.near_a);
        if (scratch.near_a.empty()) return false;
        members_near(members.points_of(b), boxes[a], reach, scratch.near_b);
        return !scratch.near_b.empty() && any_within(scratch.near_a, scratch.near_b, reach);
    };
    // A sweep over every box costs about as much whatever the share of changed patches; a search
    // from each changed one pays where few changed (a map's scan joins a few per cent).
    std::vector<std::uint32_t> from;
    std::size_t used = 0;
    for (std::size_t s = 0; s < ns; ++s) {
        used += with_members[s];
        if (with_members[s] && changed[s]) from.push_back(static_cast<std::uint32_t>(s));
    }
    const bool few = from.size() * kFewChanged < used;
    const auto homes = few ? box_pairs_of(ball, with_members, from, 0.0, threads, near_homes)
                           : near_box_pairs(ball, with_members, 0.0, threads, near_homes);
    const auto touching =
        few ? box_pairs_of(boxes, with_members, from, reach, threads, members_touch)
            : near_box_pairs(boxes, with_members, reach, threads, members_touch);
    const std::vector<std::uint64_t> found = merged_unique({&touching, &homes});
    std::vector<std::uint64_t> all;
    all.reserve(found.size() + known.size());
    std::set_union(found.begin(), found.end(), known.begin(), known.end(), std::back_inserter(all));
    return all;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> adjacent_patch_pairs(
    const PatchMembers& members, std::span<const Surface> surfaces, double reach, int threads) {
    const std::size_t ns = surfaces.size();
    std::vector<Aabb> boxes(ns);
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(ns); ++k) {
        const auto s = static_cast<std::size_t>(k);
        for (const Vec3f& x : members.points_of(s)) boxes[s].add(x.cast<double>());
    }
    const std::vector<std::uint8_t> all(ns, 1);
    const std::vector<std::uint64_t> packed =
        adjacent_patch_keys(members, surfaces, boxes, all, {}, reach, threads);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(packed.size());
    for (std::size_t k = 0; k < packed.size(); ++k) pairs[k] = pair_of_key(packed[k]);
    return pairs;
}

}  // namespace surfgrow
