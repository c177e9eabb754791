// The patch graph against brute force: every pair of member points within reach, every pair of
// homes within the sum of their radii, and nothing else, for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "surfgrow/planes/bound_plane_memo.hpp"
#include "surfgrow/planes/patch_adjacency.hpp"
#include "surfgrow/planes/patch_members.hpp"

namespace surfgrow {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

struct Patches {
    std::vector<Vec3f> points;
    std::vector<std::int32_t> labels;
    std::vector<Surface> surfaces;
    std::vector<std::uint8_t> used;
};

// Points on the two faces of a plate `thickness` thick and on a wall across it, cut into patches
// around random homes (each point to the nearest home within 40 mm, else none), with radii from
// 5 to 60 mm: small mosaics, large interlocking patches, patches with no members, one patch
// scattered over everything, labels -1, a NaN point.
Patches random_patches(std::uint64_t seed, double thickness, const Vec3d& at) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Patches p;
    for (int i = 0; i < 6000; ++i) {
        const double x = u(rng) * 0.4, y = u(rng) * 0.3;
        const Vec3d q = i % 3 == 0   ? Vec3d(x, y, 0)
                        : i % 3 == 1 ? Vec3d(x, y, thickness)
                                     : Vec3d(0.2, y, 0.3 * u(rng));
        p.points.push_back((q + at).cast<float>());
    }
    p.points.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f);
    const int n = 300;
    for (int s = 0; s < n; ++s) {
        Surface f;
        f.home = p.points[static_cast<std::size_t>(u(rng) * 6000)].cast<double>();
        f.radius = 0.005 + 0.055 * std::pow(u(rng), 3);
        p.surfaces.push_back(f);
    }
    for (const Vec3f& q : p.points) {
        std::int32_t best = -1;
        double d_best = 0.04;
        for (int s = 0; s < n; ++s) {
            // Every 7th surface takes no points; the rest by distance to their home.
            if (s % 7 == 0) continue;
            const double d =
                (p.surfaces[static_cast<std::size_t>(s)].home - q.cast<double>()).norm();
            if (d < d_best) d_best = d, best = s;
        }
        p.labels.push_back(std::isfinite(q.x()) ? best : 3);
    }
    // One patch scattered over the whole cloud: its box searches everything.
    Surface scattered;
    scattered.home = Vec3d(0.2, 0.15, 0.1) + at;
    scattered.radius = 0.01;
    p.surfaces.push_back(scattered);
    for (std::size_t i = 0; i + 1 < p.points.size(); i += 97) p.labels[i] = n;
    p.used.assign(p.surfaces.size(), 0);
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i)
        if (p.labels[i] >= 0) p.used[static_cast<std::size_t>(p.labels[i])] = 1;
    return p;
}

Pairs brute_force(const Patches& p, double reach) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    auto add = [&](std::int32_t a, std::int32_t b) {
        const auto x = static_cast<std::uint32_t>(a), y = static_cast<std::uint32_t>(b);
        out.insert({std::min(x, y), std::max(x, y)});
    };
    for (std::size_t i = 0; i < p.points.size(); ++i)
        for (std::size_t j = i + 1; j < p.points.size(); ++j) {
            const std::int32_t a = p.labels[i], b = p.labels[j];
            if (a < 0 || b < 0 || a == b || !is_finite(p.points[i]) || !is_finite(p.points[j]))
                continue;
            if ((p.points[i].cast<double>() - p.points[j].cast<double>()).norm() <= reach)
                add(a, b);
        }
    for (std::size_t a = 0; a < p.surfaces.size(); ++a)
        for (std::size_t b = a + 1; b < p.surfaces.size(); ++b)
            if (p.used[a] && p.used[b] &&
                (p.surfaces[a].home - p.surfaces[b].home).norm() <=
                    p.surfaces[a].radius + p.surfaces[b].radius)
                add(static_cast<std::int32_t>(a), static_cast<std::int32_t>(b));
    return {out.begin(), out.end()};
}

TEST(PatchAdjacency, EqualsBruteForceForAnyThreadCount) {
    // Near the origin, and 2 km from it, where float rounding (0.1 mm) is a visible share of
    // the reach: the search in float must still find every pair the exact test keeps.
    const Vec3d far(1500.0, -1300.0, 40.0);
    for (const double thickness : {0.004, 0.02}) {
        for (const std::uint64_t seed : {1u, 2u, 3u}) {
            const Patches p = random_patches(seed, thickness, seed == 3 ? far : Vec3d::Zero());
            const PatchMembers members =
                collect_patch_members(p.points, p.labels, p.surfaces.size());
            for (const double reach : {0.003, 0.006, 0.015}) {
                const Pairs truth = brute_force(p, reach);
                ASSERT_GT(truth.size(), 300u);  // the test has pairs of both kinds to find
                for (const int threads : {1, 3}) {
                    const Pairs got = adjacent_patch_pairs(members, p.surfaces, reach, threads);
                    EXPECT_EQ(got, truth) << "plate " << thickness << ", seed " << seed
                                          << ", reach " << reach << ", " << threads << " threads";
                }
            }
        }
    }
}

std::vector<std::uint64_t> keys_of(const Pairs& pairs) {
    std::vector<std::uint64_t> keys;
    for (const auto& [a, b] : pairs) keys.push_back(pair_key(a, b));
    return keys;
}

TEST(PatchAdjacency, PairsSoughtWhereMembersChangedEqualBruteForce) {
    // A map's patches gain members at the end of the cloud: the pairs found before, among the
    // unchanged patches, stay; only those of a changed patch are sought. A few changed patches
    // take the search from each of them, most the sweep over every box: both give the truth.
    for (const std::uint64_t seed : {1u, 2u}) {
        const Patches after = random_patches(seed, 0.004, Vec3d::Zero());
        // Every 40th patch new (no members before), or every patch with the second half of its
        // members new.
        for (const std::uint32_t every : {40u, 1u}) {
            Patches before = after;
            const std::size_t from = every == 1 ? after.points.size() / 2 : 0;
            for (std::size_t i = from; i < after.points.size(); ++i)
                if (after.labels[i] >= 0 &&
                    static_cast<std::uint32_t>(after.labels[i]) % every == 0)
                    before.labels[i] = -1;
            const std::size_t ns = after.surfaces.size();
            for (const double reach : {0.003, 0.015}) {
                const PatchMembers old = collect_patch_members(before.points, before.labels, ns);
                const auto known = keys_of(adjacent_patch_pairs(old, before.surfaces, reach, 1));
                const PatchMembers now = collect_patch_members(after.points, after.labels, ns);
                std::vector<Aabb> boxes(ns);
                std::vector<std::uint8_t> changed(ns, 0);
                for (std::size_t s = 0; s < ns; ++s) {
                    for (const Vec3f& x : now.points_of(s)) boxes[s].add(x.cast<double>());
                    changed[s] = now.of(s).size() != old.of(s).size();
                }
                const std::size_t count = static_cast<std::size_t>(
                    std::count(changed.begin(), changed.end(), std::uint8_t{1}));
                ASSERT_GT(count, 0u);
                const auto truth = keys_of(brute_force(after, reach));
                if (every > 1) {
                    ASSERT_GT(truth.size(), known.size());  // the new patches' pairs
                }
                for (const int threads : {1, 3}) {
                    EXPECT_EQ(adjacent_patch_keys(now, after.surfaces, boxes, changed, known, reach,
                                                  threads),
                              truth)
                        << "seed " << seed << ", " << count << " changed, reach " << reach;
                }
            }
        }
    }
}

TEST(PatchMembers, EachSurfacesPointsInInputOrderForAnyThreadCount) {
    // Labels of every kind: none, a surface with no members, NaN points, runs and singletons.
    std::vector<Vec3f> points;
    std::vector<std::int32_t> labels;
    const std::size_t surfaces = 7;
    for (std::uint32_t i = 0; i < 5000; ++i) {
        const float x = static_cast<float>(i);
        points.emplace_back(x, i % 97 == 0 ? std::nanf("") : -x, 1.f);
        const std::uint32_t h = (i * 2654435761u) >> 24;
        labels.push_back(h % 9 == 0 ? -1 : static_cast<std::int32_t>(i < 2000 ? h % 3 : h % 7));
        if (labels.back() == 5) labels.back() = 6;  // surface 5 keeps no member
    }
    for (const int threads : {1, 2, 3, 8}) {
        const PatchMembers m = collect_patch_members(points, labels, surfaces, threads);
        ASSERT_EQ(m.offset.size(), surfaces + 1);
        for (std::size_t s = 0; s < surfaces; ++s) {
            std::vector<std::uint32_t> truth;
            for (std::uint32_t i = 0; i < labels.size(); ++i)
                if (labels[i] == static_cast<std::int32_t>(s) && is_finite(points[i]))
                    truth.push_back(i);
            const auto got = m.of(s);
            EXPECT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), truth)
                << "surface " << s << ", " << threads << " threads";
            for (std::size_t k = 0; k < got.size(); ++k)
                EXPECT_EQ(m.points_of(s)[k], points[got[k]]);
        }
        EXPECT_TRUE(m.of(5).empty());
    }
}

TEST(PatchMembers, ExtendedByLaterPointsAreTheListsCollectedAnew) {
    // A map's cloud: 3000 points with 4 surfaces, then 2000 more whose labels reach 6 surfaces
    // (old ones gain points, new ones appear, one old surface gains none).
    std::vector<Vec3f> points;
    std::vector<std::int32_t> labels;
    for (std::uint32_t i = 0; i < 5000; ++i) {
        const float x = static_cast<float>(i);
        points.emplace_back(x, i % 89 == 0 ? std::nanf("") : 2 * x, 0.f);
        const std::uint32_t h = (i * 2654435761u) >> 24;
        labels.push_back(h % 7 == 0 ? -1 : static_cast<std::int32_t>(i < 3000 ? h % 4 : h % 6));
        if (i >= 3000 && labels.back() == 2) labels.back() = 5;
    }
    const std::span<const Vec3f> first_points(points.data(), 3000);
    const std::span<const std::int32_t> first_labels(labels.data(), 3000);
    for (const int threads : {1, 2, 3}) {
        const PatchMembers truth = collect_patch_members(points, labels, 6, threads);
        const PatchMembers got = extend_patch_members(
            collect_patch_members(first_points, first_labels, 4, threads), points, labels, 3000, 6);
        EXPECT_EQ(got.offset, truth.offset) << threads << " threads";
        EXPECT_EQ(got.index, truth.index) << threads << " threads";
        EXPECT_TRUE(got.point == truth.point) << threads << " threads";
    }
    const PatchMembers truth = collect_patch_members(points, labels, 6);
    // Extended by nothing: the same lists.
    EXPECT_EQ(extend_patch_members(truth, points, labels, 5000, 6).index, truth.index);
    // Scan by scan: 3000, 3200, 3500, then 5000 points. The third step fits in the room the
    // second left, its lists moved in place.
    const auto first = [&](std::size_t n) {
        return collect_patch_members(std::span(points).first(n), std::span(labels).first(n), 6);
    };
    PatchMembers m = collect_patch_members(first_points, first_labels, 4);
    std::size_t seen = 3000;
    for (const std::size_t n : {3200, 3500, 5000}) {
        const std::size_t room = m.index.capacity();
        m = extend_patch_members(std::move(m), std::span(points).first(n),
                                 std::span(labels).first(n), seen, 6);
        seen = n;
        const PatchMembers anew = first(n);
        EXPECT_EQ(m.offset, anew.offset) << n << " points";
        EXPECT_EQ(m.index, anew.index) << n << " points";
        EXPECT_TRUE(m.point == anew.point) << n << " points";
        if (n == 3500) {
            EXPECT_EQ(m.index.capacity(), room);
        }
    }
}

TEST(PatchMembers, AMemoOfAnotherCloudIsNotExtended) {
    // The memo of a cloud's first 300 points; the cloud then grows by 200. Extended where the
    // first 300 are those it saw; collected anew where a label among them changed.
    std::vector<Vec3f> points;
    std::vector<std::int32_t> labels;
    for (std::uint32_t i = 0; i < 500; ++i) {
        points.emplace_back(static_cast<float>(i), 0.f, 0.f);
        labels.push_back(static_cast<std::int32_t>(i % 3));
    }
    auto memo_of = [&](std::span<const std::int32_t> seen) {
        BoundPlaneMemo memo;
        memo.members = collect_patch_members(std::span(points).first(300), seen.first(300), 3);
        memo.member_points = 300;
        for (std::size_t s = 0; s < 3; ++s) {
            memo.counts.push_back(static_cast<std::uint32_t>(memo.members.of(s).size()));
            memo.last.push_back(memo.members.of(s).back());
        }
        return memo;
    };
    const PatchMembers truth = collect_patch_members(points, labels, 3);
    BoundPlaneMemo memo = memo_of(labels);
    EXPECT_EQ(patch_members(memo, points, labels, 3, 1).index, truth.index);
    EXPECT_TRUE(memo.members.index.empty());  // taken out: remembered again after the call
    EXPECT_EQ(memo.member_points, 0u);
    // Patch 0's last point in the memo's cloud now belongs to patch 1.
    std::vector<std::int32_t> changed = labels;
    changed[297] = 1;
    memo = memo_of(labels);
    EXPECT_EQ(patch_members(memo, points, changed, 3, 1).index,
              collect_patch_members(points, changed, 3).index);
    // A shorter cloud than the memo's.
    memo = memo_of(labels);
    EXPECT_EQ(
        patch_members(memo, std::span(points).first(200), std::span(labels).first(200), 3, 1).index,
        collect_patch_members(std::span(points).first(200), std::span(labels).first(200), 3).index);
}

TEST(PatchAdjacency, MembersAloneMakeNeighboursAcrossAnyHomeDistance) {
    // Two long strips meeting end to end: their homes far apart, their ends 2 mm apart.
    Patches p;
    for (int i = 0; i <= 100; ++i) {
        p.points.emplace_back(0.001f * static_cast<float>(i), 0.f, 0.f);
        p.labels.push_back(0);
        p.points.emplace_back(0.102f + 0.001f * static_cast<float>(i), 0.f, 0.f);
        p.labels.push_back(1);
    }
    p.surfaces.resize(2);
    p.surfaces[0].home = Vec3d(0, 0, 0);
    p.surfaces[1].home = Vec3d(0.202, 0, 0);
    p.surfaces[0].radius = p.surfaces[1].radius = 0.01;
    p.used = {1, 1};
    const PatchMembers members = collect_patch_members(p.points, p.labels, 2);
    EXPECT_EQ(adjacent_patch_pairs(members, p.surfaces, 0.0021, 1), (Pairs{{0, 1}}));
    EXPECT_TRUE(adjacent_patch_pairs(members, p.surfaces, 0.0019, 1).empty());
}

}  // namespace
}  // namespace surfgrow
