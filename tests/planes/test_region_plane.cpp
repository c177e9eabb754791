// A region's plane extended by the points it gained (a map's next scan) against the plane fitted
// anew: the same plane, its boundary within a raster cell; what it cannot extend is fitted anew.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "support/test_support.hpp"
#include "surfgrow/planes/detail/region_plane.hpp"

namespace surfgrow::detail {
namespace {

// A strip of `patches` patches 0.1 m x 0.3 m side by side along x on the plane z = 0 (noise
// 0.5 mm), points 5 mm apart. The cloud holds every patch's first `share` of its points, then
// the rest (a map: the second scan's points at the end), or only the first part.
struct Strip {
    std::vector<Vec3f> points;
    std::vector<std::int32_t> labels;
    std::vector<Surface> surfaces;
};

Strip strip(int patches, double share, bool rest, double tilt_deg = 0.0) {
    Strip s;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 0.0005);
    std::vector<Vec3f> later;
    std::vector<std::int32_t> later_labels;
    const double slope = std::tan(tilt_deg * M_PI / 180);
    for (int p = 0; p < patches; ++p) {
        Surface f;
        f.home = Vec3d(0.1 * p + 0.05, 0.15, 0);
        f.centroid = f.home;
        f.radius = 0.08;
        f.neighbours = 20;
        s.surfaces.push_back(f);
        int k = 0;
        const int count = 20 * 60;
        for (int i = 0; i < 20; ++i)
            for (int j = 0; j < 60; ++j, ++k) {
                const double x = 0.1 * p + 0.005 * i + 0.0025, y = 0.005 * j + 0.0025;
                const bool first = k < share * count;
                const double z = noise(rng) + (first ? 0.0 : slope * x);
                (first ? s.points : later).emplace_back(float(x), float(y), float(z));
                (first ? s.labels : later_labels).push_back(p);
            }
    }
    if (rest) {
        s.points.insert(s.points.end(), later.begin(), later.end());
        s.labels.insert(s.labels.end(), later_labels.begin(), later_labels.end());
    }
    return s;
}

// What compute_bound_planes hands a region: its members, per-patch moments and boxes.
struct Region {
    PatchMembers members;
    std::vector<CentredMoments> moments;
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> patches;
    CentredMoments all;
    Vec3d judge = Vec3d::Zero();
    std::vector<std::uint32_t> counts;  // members per patch

    Region(const Strip& s, std::vector<std::uint32_t> list) : patches(std::move(list)) {
        const std::size_t ns = s.surfaces.size();
        members = collect_patch_members(s.points, s.labels, ns);
        moments.resize(ns);
        boxes.resize(ns);
        for (std::size_t p = 0; p < ns; ++p) {
            Moments m;
            for (const Vec3f& x : members.points_of(p)) {
                m.add(x.cast<double>() - s.surfaces[p].home);
                boxes[p].add(x.cast<double>());
            }
            moments[p] = CentredMoments::of(m, s.surfaces[p].home);
            counts.push_back(static_cast<std::uint32_t>(members.of(p).size()));
        }
        for (const std::uint32_t p : patches) all.merge(moments[p]);
    }
    [[nodiscard]] RegionInput input(const Strip& s) const {
        return {s.surfaces, members, moments, boxes, patches, all, judge};
    }
};

BoundPlaneConfig config() {
    BoundPlaneConfig c;
    c.mu = 0.024;
    c.resolution = 0.01;
    c.simplify_tolerance = 0.01;
    c.closing_radius = 0.015;
    return c;
}

// The plane `was` fitted on the first part of strip `before`, with its state.
FittedRegion fitted(const Strip& before, const std::vector<std::uint32_t>& patches) {
    const Region r(before, patches);
    FittedRegion f;
    f.moments = r.all;
    f.judge = r.judge;
    f.plane = fit_region(r.input(before), config(), &f.state);
    return f;
}

void expect_same_plane_within_a_cell(const BoundPlane& got, const BoundPlane& truth) {
    EXPECT_EQ(got.normal, truth.normal);
    EXPECT_EQ(got.centroid, truth.centroid);
    EXPECT_EQ(got.rms, truth.rms);
    EXPECT_EQ(got.point_count, truth.point_count);
    EXPECT_EQ(got.patches, truth.patches);
    EXPECT_EQ(got.bounds.min, truth.bounds.min);
    EXPECT_EQ(got.bounds.max, truth.bounds.max);
    EXPECT_NEAR(got.u_axis.dot(got.normal), 0.0, 1e-12);
    EXPECT_NEAR(got.v_axis.norm(), 1.0, 1e-12);
    EXPECT_LE(std::abs(got.area - truth.area),
              test::boundary_length(truth.polygons) * config().resolution);
    EXPECT_EQ(got.polygons.size(), truth.polygons.size());
}

TEST(RegionPlane, ExtendedByTheNewPointsItIsThePlaneFittedAnewWithinACell) {
    const Strip before = strip(5, 0.6, false), after = strip(5, 0.6, true);
    const FittedRegion was = fitted(before, {0, 1, 2, 3, 4});
    ASSERT_FALSE(was.state.cells.count.empty());
    const Region now(after, {0, 1, 2, 3, 4});
    const std::vector<std::uint32_t> known = Region(before, {}).counts;
    RegionState state;
    const std::optional<BoundPlane> got =
        extend_region(now.input(after), was, known, config(), state);
    ASSERT_TRUE(got);
    const BoundPlane truth = fit_region(now.input(after), config());
    expect_same_plane_within_a_cell(*got, truth);
    // The strip is 0.5 m x 0.3 m; the polygon encloses the cells' centres.
    EXPECT_NEAR(got->area, 0.15, 0.01);
    // The state counts every point, in the frame of the first fit.
    std::uint64_t counted = 0;
    for (const std::uint32_t c : state.cells.count) counted += c;
    EXPECT_EQ(counted, after.points.size());
    EXPECT_EQ(state.anchor, was.state.anchor);
}

TEST(RegionPlane, APatchThatLeftTakesItsPointsAlong) {
    // Patch 4 is another region's now: its 0.1 m x 0.3 m go from the boundary.
    const Strip before = strip(5, 0.6, false), after = strip(5, 0.6, true);
    const FittedRegion was = fitted(before, {0, 1, 2, 3, 4});
    const Region now(after, {0, 1, 2, 3});
    RegionState state;
    const std::optional<BoundPlane> got =
        extend_region(now.input(after), was, Region(before, {}).counts, config(), state);
    ASSERT_TRUE(got);
    expect_same_plane_within_a_cell(*got, fit_region(now.input(after), config()));
    EXPECT_NEAR(got->area, 0.12, 0.01);
    std::uint64_t counted = 0;
    for (const std::uint32_t c : state.cells.count) counted += c;
    EXPECT_EQ(counted, static_cast<std::uint64_t>(now.all.n));
}

TEST(RegionPlane, AFaceOfManyPointsIsFittedOnASampleOfThem) {
    // 240,000 points (a fused map's web): the fit's passes read an even sample of 65,536, and
    // the plane stays on the truth (z = 0, noise 0.5 mm) within what the noise allows: across
    // the 0.3 m width, 0.5 mm / (0.087 m x sqrt(65,536)) = 0.0013 degrees.
    const Strip s = strip(200, 1.0, false);
    std::vector<std::uint32_t> all(200);
    for (std::uint32_t p = 0; p < 200; ++p) all[p] = p;
    const Region r(s, all);
    ASSERT_GT(r.all.n, 200000);
    const BoundPlane plane = fit_region(r.input(s), config());
    EXPECT_LT(std::acos(std::abs(plane.normal.z())) * 180 / M_PI, 0.01);
    EXPECT_LT(std::abs(plane.centroid.z()), 2e-5);
    EXPECT_NEAR(plane.rms, 0.0005, 0.00002);  // of all the points
    EXPECT_NEAR(plane.area, 20.0 * 0.3, 0.3);
}

TEST(RegionPlane, WhatItCannotExtendIsFittedAnew) {
    const std::vector<std::uint32_t> all{0, 1, 2, 3, 4};
    RegionState state;
    state.anchor = Vec3d(1, 2, 3);  // untouched when nothing is extended
    const auto untouched = [&] { return state.anchor == Vec3d(1, 2, 3); };
    {  // the region more than doubled (40 % of its points seen before)
        const Strip before = strip(5, 0.4, false), after = strip(5, 0.4, true);
        const Region now(after, all);
        EXPECT_FALSE(extend_region(now.input(after), fitted(before, all), Region(before, {}).counts,
                                   config(), state));
        EXPECT_TRUE(untouched());
    }
    {  // the new points tilt the plane by more than kExtendDeg
        const Strip before = strip(5, 0.6, false), after = strip(5, 0.6, true, 3.0);
        const Region now(after, all);
        const BoundPlane anew = fit_region(now.input(after), config());
        ASSERT_GT(std::acos(anew.normal.dot(Vec3d::UnitZ())) * 180 / M_PI, kExtendDeg);
        EXPECT_FALSE(extend_region(now.input(after), fitted(before, all), Region(before, {}).counts,
                                   config(), state));
        EXPECT_TRUE(untouched());
    }
    {  // a plane fitted without a state (degenerate planes keep none)
        const Strip before = strip(5, 0.6, false), after = strip(5, 0.6, true);
        FittedRegion was = fitted(before, all);
        was.state = {};
        const Region now(after, all);
        EXPECT_FALSE(
            extend_region(now.input(after), was, Region(before, {}).counts, config(), state));
        EXPECT_TRUE(untouched());
    }
}

}  // namespace
}  // namespace surfgrow::detail
