#include "surfgrow/planes/patch_adjacency.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

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

// Boxes are Aabbs in double: exact bounds of float points.
bool near_on_axis(const Aabb& a, const Aabb& b, int axis, double pad) {
    return b.min[axis] - a.max[axis] <= pad && a.min[axis] - b.max[axis] <= pad;
}

// What a pair test may reuse between calls on one thread.
struct Scratch {
    std::vector<Vec3d> near_a, near_b;
};

// The keys of the pairs of boxes among those `use` marks that lie within `pad` of each other on
// every axis and that `touch(a, b, scratch)` accepts, one list per thread. Such boxes' centres
// are within 2 e + pad of each other on every axis, e the larger box's largest half extent: so
// each pair is sought from its larger box, over an index of the centres whose cubes suit the
// common size. A margin keeps the search from deciding a tie; the box test and `touch` decide.
template <class Touch>
std::vector<std::vector<std::uint64_t>> near_box_pairs(const std::vector<Aabb>& box,
                                                       const std::vector<std::uint8_t>& use,
                                                       double pad, int threads, Touch&& touch) {
    const std::size_t n = box.size();
    std::vector<Vec3f> centre(n, Vec3f::Zero());
    std::vector<double> half(n, 0.0), halves;
    for (std::size_t s = 0; s < n; ++s) {
        if (!use[s]) continue;
        centre[s] = ((box[s].min + box[s].max) / 2).cast<float>();
        half[s] = box[s].size().maxCoeff() / 2;
        halves.push_back(half[s]);
    }
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
// patch), and only then are members near the other's box compared. Sorted, unique pairs
// (a < b); the final sort makes the result independent of the thread count.
std::vector<std::pair<std::uint32_t, std::uint32_t>> adjacent_patch_pairs(
    const PatchMembers& members, std::span<const Surface> surfaces, double reach, int threads) {
    const std::size_t ns = surfaces.size();
    std::vector<Aabb> box(ns), ball(ns);
    std::vector<std::uint8_t> with_members(ns, 0);
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(ns); ++k) {
        const auto s = static_cast<std::size_t>(k);
        if (members.of(s).empty()) continue;
        with_members[s] = 1;
        for (const Vec3f& x : members.points_of(s)) box[s].add(x.cast<double>());
        ball[s] = {surfaces[s].home.array() - surfaces[s].radius,
                   surfaces[s].home.array() + surfaces[s].radius};
    }
    const auto homes_within_radii = [&](std::uint32_t a, std::uint32_t b, Scratch&) {
        return (surfaces[b].home - surfaces[a].home).norm() <=
               surfaces[a].radius + surfaces[b].radius;
    };
    const auto near_homes = near_box_pairs(ball, with_members, 0.0, threads, homes_within_radii);
    const auto touching = near_box_pairs(
        box, with_members, reach, threads, [&](std::uint32_t a, std::uint32_t b, Scratch& scratch) {
            if (homes_within_radii(a, b, scratch)) return false;  // the other rule has it
            members_near(members.points_of(a), box[b], reach, scratch.near_a);
            if (scratch.near_a.empty()) return false;
            members_near(members.points_of(b), box[a], reach, scratch.near_b);
            return !scratch.near_b.empty() && any_within(scratch.near_a, scratch.near_b, reach);
        });
    const std::vector<std::uint64_t> packed = merged_unique({&touching, &near_homes});
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(packed.size());
    for (std::size_t k = 0; k < packed.size(); ++k)
        pairs[k] = {static_cast<std::uint32_t>(packed[k] >> 32),
                    static_cast<std::uint32_t>(packed[k] & 0xffffffffu)};
    return pairs;
}

}  // namespace surfgrow
