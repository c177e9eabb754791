#include "surfgrow/planes/bound_plane_memo.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

namespace surfgrow {

namespace {

bool same_bits(const CentredMoments& a, const CentredMoments& b) {
    return a.n == b.n && a.mean == b.mean && a.scatter == b.scatter;
}

}  // namespace

PatchMembers patch_members(BoundPlaneMemo& memo, std::span<const Vec3f> points,
                           std::span<const std::int32_t> labels, std::size_t surfaces,
                           int threads) {
    PatchMembers old = std::move(memo.members);
    memo.members = {};
    const std::size_t from = std::exchange(memo.member_points, 0);
    const std::size_t known = old.offset.empty() ? 0 : old.offset.size() - 1;
    bool same =
        from > 0 && from <= labels.size() && known <= surfaces && known == memo.counts.size();
    for (std::size_t s = 0; same && s < known; ++s) {
        const std::uint32_t c = old.offset[s + 1] - old.offset[s];
        if (c != memo.counts[s]) same = false;
        if (!same || c == 0) continue;
        const std::uint32_t last = old.index[old.offset[s + 1] - 1];
        same = last == memo.last[s] && last < from &&
               labels[last] == static_cast<std::int32_t>(s) &&
               points[last] == old.point[old.offset[s + 1] - 1];
    }
    if (!same) return collect_patch_members(points, labels, surfaces, threads);
    return extend_patch_members(std::move(old), points, labels, from, surfaces);
}

KnownMembers known_members(const BoundPlaneMemo& memo, const PatchMembers& members,
                           std::span<const Surface> surfaces) {
    const std::size_t ns = surfaces.size();
    const std::size_t old = memo.counts.size();
    KnownMembers known;
    known.count.assign(ns, 0);
    if (old == 0 || old > ns) return known;
    for (std::size_t s = 0; s < old; ++s) {
        const std::uint32_t c = memo.counts[s];
        const auto of = members.of(s);
        const Surface& f = surfaces[s];
        if (f.home != memo.homes[s] || f.normal != memo.normals[s] || f.radius != memo.radii[s] ||
            f.neighbours != memo.neighbours[s] || of.size() < c ||
            (c > 0 && of[c - 1] != memo.last[s])) {
            known.count.assign(ns, 0);
            return known;
        }
        known.count[s] = c;
    }
    known.valid = true;
    return known;
}

void patch_sums(const BoundPlaneMemo& memo, const KnownMembers& known, const PatchMembers& members,
                std::span<const Surface> surfaces, std::vector<Moments>& moments,
                std::vector<Aabb>& boxes, int threads) {
    const std::size_t ns = surfaces.size();
    moments.assign(ns, Moments{});
    boxes.assign(ns, Aabb{});
    // Each patch's sums in its members' order, whichever thread: the same bits for any count.
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(ns); ++k) {
        const auto s = static_cast<std::size_t>(k);
        const std::uint32_t from = known.count[s];
        Moments m = from > 0 ? memo.moments[s] : Moments{};
        Aabb box = from > 0 ? memo.boxes[s] : Aabb{};
        const Vec3d& home = surfaces[s].home;
        for (const Vec3f& x : members.points_of(s).subspan(from)) {
            const Vec3d p = x.cast<double>();
            m.add(p - home);
            box.add(p);
        }
        moments[s] = m;
        boxes[s] = box;
    }
}

void remember_patches(BoundPlaneMemo& memo, const PatchMembers& members,
                      std::span<const Surface> surfaces, std::vector<Moments> moments,
                      std::vector<Aabb> boxes, double reach, std::vector<std::uint64_t> pairs) {
    const std::size_t ns = surfaces.size();
    memo.homes.resize(ns);
    memo.normals.resize(ns);
    memo.radii.resize(ns);
    memo.neighbours.resize(ns);
    memo.counts.resize(ns);
    memo.last.resize(ns);
    for (std::size_t s = 0; s < ns; ++s) {
        const Surface& f = surfaces[s];
        memo.homes[s] = f.home;
        memo.normals[s] = f.normal;
        memo.radii[s] = f.radius;
        memo.neighbours[s] = f.neighbours;
        const auto of = members.of(s);
        memo.counts[s] = static_cast<std::uint32_t>(of.size());
        memo.last[s] = of.empty() ? 0 : of.back();
    }
    memo.moments = std::move(moments);
    memo.boxes = std::move(boxes);
    memo.reach = reach;
    memo.pairs = std::move(pairs);
}

const FittedRegion* remembered_region(const BoundPlaneMemo& memo,
                                      std::span<const std::uint32_t> patches,
                                      const BoundPlaneConfig& config) {
    if (patches.empty() || patches[0] >= memo.region_from.size() ||
        config.resolution != memo.resolution || config.closing_radius != memo.closing_radius ||
        config.simplify_tolerance != memo.simplify_tolerance)
        return nullptr;
    const std::int32_t r = memo.region_from[patches[0]];
    return r < 0 ? nullptr : &memo.regions[static_cast<std::size_t>(r)];
}

const FittedRegion* remembered_plane(const BoundPlaneMemo& memo,
                                     std::span<const std::uint32_t> patches,
                                     std::span<const std::uint8_t> changed,
                                     const CentredMoments& moments, const Vec3d& judge,
                                     const BoundPlaneConfig& config) {
    const FittedRegion* f = remembered_region(memo, patches, config);
    if (!f ||
        !std::equal(patches.begin(), patches.end(), f->plane.patches.begin(),
                    f->plane.patches.end()) ||
        !same_bits(moments, f->moments) || judge != f->judge)
        return nullptr;
    for (const std::uint32_t s : patches)
        if (changed[s]) return nullptr;
    return f;
}

void remember_planes(BoundPlaneMemo& memo, std::size_t patches,
                     std::span<const CentredMoments> moments, std::span<const Vec3d> judges,
                     std::span<const BoundPlane> planes, std::vector<RegionState> states,
                     const BoundPlaneConfig& config) {
    memo.resolution = config.resolution;
    memo.closing_radius = config.closing_radius;
    memo.simplify_tolerance = config.simplify_tolerance;
    memo.regions.resize(planes.size());
    memo.region_from.assign(patches, -1);
    for (std::size_t r = 0; r < planes.size(); ++r) {
        memo.regions[r] = {moments[r], judges[r], planes[r],
                           r < states.size() ? std::move(states[r]) : RegionState{}};
        memo.region_from[planes[r].patches[0]] = static_cast<std::int32_t>(r);
    }
}

}  // namespace surfgrow
