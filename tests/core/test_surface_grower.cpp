#include <gtest/gtest.h>

#include <stdexcept>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>

#include "support/test_support.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/plane_fit.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow {
namespace {

using test::Rect;

constexpr double kDeg = M_PI / 180.0;

// A cloud sampled from rectangles, with the true normal of every point's face.
struct Scene {
    PointCloud cloud;
    std::vector<Vec3d> face_normals;  // by label
};

Scene sample_scene(const std::vector<Rect>& faces, double spacing, double sigma,
                   std::uint64_t seed) {
    Scene s;
    std::mt19937_64 rng(seed);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        test::sample_rect(faces[f], spacing, 0.3, sigma, rng, s.cloud.points, &s.cloud.labels,
                          static_cast<int32_t>(f));
        s.face_normals.push_back(faces[f].normal());
    }
    return s;
}

// Per-point angle between the point's surface normal and its true face normal (lines, not vectors).
std::vector<double> normal_errors(const Scene& s, const GrowResult& r) {
    std::vector<double> err;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
        const int32_t l = r.labels[i];
        if (l < 0) continue;
        err.push_back(
            axis_angle_between(r.surfaces[static_cast<std::size_t>(l)].normal,
                               s.face_normals[static_cast<std::size_t>(s.cloud.labels[i])]));
    }
    return err;
}

// Invariants every result must satisfy, whatever the input.
void check_invariants(const PointCloud& cloud, const GrowerConfig& cfg, const GrowResult& r) {
    const GrowStats& st = r.stats;
    ASSERT_EQ(r.labels.size(), cloud.size());
    EXPECT_EQ(st.points_in, cloud.size());
    EXPECT_EQ(st.points_in, st.invalid_points + st.cropped_points + st.valid_points);
    EXPECT_EQ(st.surfaces, r.surfaces.size());
    EXPECT_LE(st.registered_grown, st.registered);
    EXPECT_EQ(st.valid_points, st.registered + st.noise_points);
    EXPECT_EQ(st.homes_tried, st.surfaces + st.dropped_surfaces + st.rejected_sparse +
                                  st.rejected_nonplanar + st.rejected_covered);
    EXPECT_LE(st.lone_surfaces, st.dropped_surfaces);
    std::vector<std::uint32_t> count(r.surfaces.size(), 0);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const int32_t l = r.labels[i];
        if (l < 0) continue;
        ASSERT_LT(static_cast<std::size_t>(l), r.surfaces.size());
        const Surface& s = r.surfaces[static_cast<std::size_t>(l)];
        const Vec3d p = cloud.points[i].cast<double>();
        ++count[static_cast<std::size_t>(l)];
        // Registered within the surface's plane tolerance: the user's, scaled with an adapted
        // radius; or a few noise sigmas, never above the radius ...
        if (cfg.tolerance() > 0) {
            EXPECT_NEAR(s.tolerance, cfg.tolerance() * s.radius / cfg.mu, 1e-6 * s.radius);
        }
        EXPECT_LE(s.tolerance, s.radius * (1 + 1e-6));
        EXPECT_LE(std::abs(s.plane().signed_distance(p)), s.tolerance * (1 + 1e-5) + 1e-6);
        // ... and near the home point: within its radius, or a neighbour's reach for leftovers.
        EXPECT_LE((p - s.home).norm(), s.radius + cfg.max_radius() + 1e-6);
        EXPECT_TRUE((p.array() >= s.bounds.min.array() - 1e-6).all() &&
                    (p.array() <= s.bounds.max.array() + 1e-6).all());
    }
    std::uint64_t total = 0;
    for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
        const Surface& s = r.surfaces[k];
        EXPECT_EQ(s.point_count, count[k]);
        EXPECT_GE(s.neighbours, static_cast<std::uint32_t>(cfg.min_pts));
        EXPECT_NEAR(s.normal.norm(), 1.0, 1e-9);
        EXPECT_TRUE(is_planar(s.eigenvalues, cfg.alpha));
        total += s.point_count;
    }
    EXPECT_EQ(total, st.registered);
}

GrowerConfig config_mm(double mu_mm = 12) {
    GrowerConfig c;
    c.mu = mu_mm / 1000;
    return c;
}

TEST(SurfaceGrower, NoiseFreePlaneIsRegisteredWithExactNormals) {
    const Scene s =
        sample_scene({{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15}}, 0.004, 0.0, 1);
    const GrowerConfig cfg = config_mm();
    const GrowResult r = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, r);
    EXPECT_EQ(r.stats.registered, r.stats.valid_points);
    for (const Surface& surf : r.surfaces)
        EXPECT_LT(axis_angle_between(surf.normal, Vec3d::UnitZ()), 1e-3);
    // The paper's data reduction: many points per surface.
    EXPECT_GT(r.stats.data_reduction(), 10.0);
}

TEST(SurfaceGrower, AProgressCallbackThatThrowsStopsTheRunEvenInsideTheSlabLoop) {
    // "grow" is reported from inside the slab loop's parallel region (an inactive one with one
    // thread): the exception must come out of grow(), soon, not end the process.
    const Scene s =
        sample_scene({{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 1.0, 1.0}}, 0.004, 0.0005, 1);
    for (const int threads : {1, 2}) {
        SCOPED_TRACE(threads);
        GrowerConfig cfg = config_mm();
        cfg.threads = threads;
        int grow_reports = 0, after = 0;
        cfg.progress = [&](std::string_view stage, double) {
            if (stage != "grow") return;
            if (++grow_reports > 1) ++after;
            throw std::runtime_error("stop");
        };
        EXPECT_THROW((void)grow_surfaces(s.cloud, cfg), std::runtime_error);
        EXPECT_EQ(after, 0);  // thread 0 reports nothing once it has thrown
        cfg.progress = nullptr;
        EXPECT_EQ(grow_surfaces(s.cloud, cfg).stats.registered,
                  grow_surfaces(s.cloud, config_mm()).stats.registered);
    }
}

TEST(SurfaceGrower, BoxSceneMeetsThePapersRegistrationWithAccurateNormals) {
    // A 0.6 x 0.4 x 0.3 m box sampled every 5 mm (the paper's spacing at 1 m) with 1.5 mm noise.
    const Scene s =
        sample_scene(test::box_faces({-0.3, -0.2, 0.5}, {0.3, 0.2, 0.8}), 0.005, 0.0015, 2);
    const GrowerConfig cfg = config_mm();
    const GrowResult r = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, r);
    EXPECT_GE(r.stats.registered_fraction(), 0.99);
    const auto err = normal_errors(s, r);
    const double med = test::median(err), p95 = test::quantile(err, 0.95);
    std::printf(
        "box: %zu points, %llu surfaces, grown %.2f%%, final %.2f%%, normal error median %.2f deg, "
        "p95 %.2f deg\n",
        s.cloud.size(), static_cast<unsigned long long>(r.stats.surfaces),
        100 * r.stats.registered_grown_fraction(), 100 * r.stats.registered_fraction(), med / kDeg,
        p95 / kDeg);
    EXPECT_LT(med, 3.0 * kDeg);
    EXPECT_LT(p95, 15.0 * kDeg);
}

TEST(SurfaceGrower, IBeamSceneMeetsThePapersRegistrationWithAccurateNormals) {
    const Scene s = sample_scene(test::ibeam_faces(1.0, 0.6, 0.3, 0.025, 0.014), 0.005, 0.0015, 3);
    const GrowerConfig cfg = config_mm();
    const GrowResult r = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, r);
    EXPECT_GE(r.stats.registered_fraction(), 0.99);
    const auto err = normal_errors(s, r);
    std::printf(
        "ibeam: %zu points, %llu surfaces, grown %.2f%%, final %.2f%%, normal error median %.2f "
        "deg\n",
        s.cloud.size(), static_cast<unsigned long long>(r.stats.surfaces),
        100 * r.stats.registered_grown_fraction(), 100 * r.stats.registered_fraction(),
        test::median(err) / kDeg);
    EXPECT_LT(test::median(err), 3.0 * kDeg);
}

TEST(SurfaceGrower, ByteIdenticalForAnyThreadCount) {
    const Scene s = sample_scene(test::ibeam_faces(2.0, 0.6, 0.3, 0.025, 0.014), 0.005, 0.002, 4);
    GrowerConfig cfg = config_mm();
    cfg.seed = 42;
    cfg.threads = 1;
    const GrowResult ref = grow_surfaces(s.cloud, cfg);
    ASSERT_GT(ref.surfaces.size(), 100u);
    for (int threads : {2, 3, 8}) {
        cfg.threads = threads;
        const GrowResult r = grow_surfaces(s.cloud, cfg);
        ASSERT_EQ(r.labels, ref.labels) << threads << " threads";
        ASSERT_EQ(r.surfaces.size(), ref.surfaces.size());
        for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
            const Surface &a = r.surfaces[k], &b = ref.surfaces[k];
            ASSERT_EQ(a.home, b.home);
            ASSERT_EQ(a.normal, b.normal);
            ASSERT_EQ(a.centroid, b.centroid);
            ASSERT_EQ(a.eigenvalues, b.eigenvalues);
            ASSERT_EQ(a.point_count, b.point_count);
            ASSERT_EQ(a.mean_residual, b.mean_residual);
        }
    }
}

TEST(SurfaceGrower, SeedChangesHomePointsButNotTheOutcome) {
    const Scene s = sample_scene(test::box_faces({0, 0, 0}, {0.4, 0.3, 0.2}), 0.005, 0.001, 5);
    GrowerConfig cfg = config_mm();
    cfg.seed = 1;
    const GrowResult a = grow_surfaces(s.cloud, cfg);
    cfg.seed = 2;
    const GrowResult b = grow_surfaces(s.cloud, cfg);
    EXPECT_NE(a.labels, b.labels);
    EXPECT_NEAR(double(a.stats.surfaces), double(b.stats.surfaces),
                0.05 * double(a.stats.surfaces));
    EXPECT_NEAR(a.stats.registered_fraction(), b.stats.registered_fraction(), 0.005);
}

TEST(SurfaceGrower, EmptyAndInvalidCloudsGiveNoSurfaces) {
    const GrowerConfig cfg = config_mm();
    const GrowResult empty = grow_surfaces(PointCloud{}, cfg);
    EXPECT_TRUE(empty.surfaces.empty());
    EXPECT_TRUE(empty.labels.empty());
    EXPECT_EQ(empty.stats.valid_points, 0u);

    PointCloud nans;
    nans.points.assign(100, Vec3f(std::nanf(""), 0, 0));
    const GrowResult r = grow_surfaces(nans, cfg);
    EXPECT_TRUE(r.surfaces.empty());
    EXPECT_EQ(r.stats.invalid_points, 100u);
    EXPECT_EQ(r.labels, std::vector<int32_t>(100, -1));
}

TEST(SurfaceGrower, InvalidPointsKeepTheirPlaceAndLabelMinusOne) {
    Scene s = sample_scene({{{0, 0, 1}, Vec3d::UnitX(), Vec3d::UnitY(), 0.1, 0.1}}, 0.004, 0.0, 6);
    const std::size_t n = s.cloud.size();
    for (std::size_t i = 0; i < n; i += 10) s.cloud.points[i] = Vec3f(INFINITY, 0, std::nanf(""));
    const GrowResult r = grow_surfaces(s.cloud, config_mm());
    check_invariants(s.cloud, config_mm(), r);
    EXPECT_EQ(r.stats.invalid_points, (n + 9) / 10);
    for (std::size_t i = 0; i < n; ++i) {
        if (i % 10 == 0) {
            EXPECT_EQ(r.labels[i], -1);
        } else {
            EXPECT_GE(r.labels[i], 0) << i;
        }
    }
}

TEST(SurfaceGrower, IsolatedNoisePointsAreRejectedAsNoise) {
    Scene s = sample_scene({{{0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.1, 0.1}}, 0.004, 0.0, 7);
    const std::size_t plane_points = s.cloud.size();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<float> u(0.3f, 3.f);
    for (int i = 0; i < 200; ++i) s.cloud.points.emplace_back(u(rng), u(rng), u(rng));
    const GrowResult r = grow_surfaces(s.cloud, config_mm());
    EXPECT_EQ(r.stats.noise_points, 200u);
    EXPECT_GE(r.stats.rejected_sparse, 200u);
    for (std::size_t i = plane_points; i < s.cloud.size(); ++i) EXPECT_EQ(r.labels[i], -1);
}

TEST(SurfaceGrower, LeftoverPassClosesTheGapAtEdges) {
    const Scene s = sample_scene(test::box_faces({0, 0, 0}, {0.3, 0.3, 0.3}), 0.005, 0.0015, 8);
    GrowerConfig cfg = config_mm();
    cfg.attach_leftovers = false;
    const GrowResult plain = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, plain);
    EXPECT_EQ(plain.stats.registered, plain.stats.registered_grown);
    cfg.attach_leftovers = true;
    const GrowResult closed = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, closed);
    EXPECT_EQ(closed.stats.registered_grown, plain.stats.registered_grown);
    EXPECT_GT(closed.stats.registered, plain.stats.registered);
    EXPECT_GE(closed.stats.registered_fraction(), 0.99);
    // Attaching must not cost accuracy: median normal error stays put.
    EXPECT_LT(test::median(normal_errors(s, closed)),
              test::median(normal_errors(s, plain)) + 0.5 * kDeg);
}

TEST(SurfaceGrower, AdaptiveRadiusRegistersSparseFarSurfaces) {
    // 20 mm spacing (the URG at ~3 m): a 12 mm ball holds one or two points.
    const Scene s =
        sample_scene({{{0, 0, 3}, Vec3d::UnitX(), Vec3d::UnitY(), 0.5, 0.5}}, 0.02, 0.002, 9);
    GrowerConfig cfg = config_mm();
    cfg.adaptive_factor = 1.0;  // the paper's fixed mu
    const GrowResult fixed = grow_surfaces(s.cloud, cfg);
    EXPECT_LT(fixed.stats.registered_fraction(), 0.1);
    cfg.adaptive_factor = 8.0;
    const GrowResult adaptive = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, adaptive);
    EXPECT_GE(adaptive.stats.registered_fraction(), 0.99);
    EXPECT_EQ(adaptive.stats.adapted_surfaces, adaptive.stats.surfaces);
    std::vector<double> err;
    for (const Surface& surf : adaptive.surfaces) {
        EXPECT_GT(surf.radius, cfg.mu);
        err.push_back(axis_angle_between(surf.normal, Vec3d::UnitZ()));
    }
    // ~18 points over 48 mm with 2 mm noise: about 1.3 degrees by theory.
    EXPECT_LT(test::median(err), 2.0 * kDeg);
    EXPECT_LT(test::quantile(err, 1.0), 10.0 * kDeg);
}

TEST(SurfaceGrower, WorkspaceCropKeepsOnlyPointsInside) {
    const Scene s =
        sample_scene({{{0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 1.0, 1.0}}, 0.01, 0.0, 10);
    GrowerConfig cfg = config_mm(25);
    cfg.crop.radius = 0.5;
    cfg.crop.center = Vec3d::Zero();
    const GrowResult r = grow_surfaces(s.cloud, cfg);
    check_invariants(s.cloud, cfg, r);
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
        if (s.cloud.points[i].norm() > 0.5f) {
            EXPECT_EQ(r.labels[i], -1);
        }
    }
    EXPECT_GT(r.stats.cropped_points, s.cloud.size() / 2);
    EXPECT_GE(r.stats.registered_fraction(), 0.99);

    cfg.crop = {};
    Aabb box;
    box.add({-0.2, -0.2, -1});
    box.add({0.2, 0.2, 1});
    cfg.crop.box = box;
    const GrowResult b = grow_surfaces(s.cloud, cfg);
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
        if (!box.contains(s.cloud.points[i].cast<double>())) {
            EXPECT_EQ(b.labels[i], -1);
        }
    }
}

TEST(SurfaceGrower, NormalsFaceTheViewpointOrTheirScanOrigin) {
    const Scene s =
        sample_scene(test::box_faces({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}), 0.01, 0.0, 11);
    GrowerConfig cfg = config_mm(30);
    cfg.viewpoint = Vec3d(0, 0, 0);  // inside the box: every normal points inwards
    GrowResult r = grow_surfaces(s.cloud, cfg);
    EXPECT_EQ(r.stats.orientation, OrientationSource::kViewpoint);
    for (const Surface& surf : r.surfaces) EXPECT_GT(surf.normal.dot(-surf.home), 0.0);

    // Two scans from outside, on opposite sides: each surface faces its home point's scanner.
    PointCloud fused = s.cloud;
    fused.scan_origins = {Vec3d(3, 0, 0), Vec3d(-3, 0, 0)};
    fused.scan_index.resize(fused.size());
    for (std::size_t i = 0; i < fused.size(); ++i)
        fused.scan_index[i] = fused.points[i].x() >= 0 ? 0 : 1;
    cfg.viewpoint.reset();
    r = grow_surfaces(fused, cfg);
    EXPECT_EQ(r.stats.orientation, OrientationSource::kScanOrigins);
    for (const Surface& surf : r.surfaces) {
        const Vec3d origin = surf.home.x() >= 0 ? Vec3d(3, 0, 0) : Vec3d(-3, 0, 0);
        EXPECT_GE(surf.normal.dot(origin - surf.home), 0.0);
    }
}

TEST(SurfaceGrower, WithoutViewpointUsesFrameOriginOrFacesUp) {
    // A sensor-frame scan of a floor below the origin: normals face the origin (up).
    const Scene floor =
        sample_scene({{{1, 0, -0.8}, Vec3d::UnitX(), Vec3d::UnitY(), 0.3, 0.3}}, 0.005, 0.0, 12);
    GrowResult r = grow_surfaces(floor.cloud, config_mm());
    EXPECT_EQ(r.stats.orientation, OrientationSource::kFrameOrigin);
    ASSERT_TRUE(r.stats.range_known);
    for (const Surface& surf : r.surfaces) EXPECT_GT(surf.normal.z(), 0.9);
    // Georeferenced: the same floor 5 km from the origin faces +z by rule.
    Scene far = floor;
    for (auto& p : far.cloud.points) p += Vec3f(5000, 0, 0);
    far.cloud.points.front() = far.cloud.points.front();
    r = grow_surfaces(far.cloud, config_mm());
    EXPECT_EQ(r.stats.orientation, OrientationSource::kUp);
    EXPECT_FALSE(r.stats.range_known);
    for (const Surface& surf : r.surfaces) EXPECT_GT(surf.normal.z(), 0.9);
}

TEST(SurfaceGrower, AFloorThroughTheFrameOriginFacesUp) {
    // A map-frame cloud with its origin on the floor (as the real tilted-steps.pcd): the origin
    // sees the floor edge-on, so "facing the origin" flipped its normals by noise alone. Beyond
    // the grazing limit they face +z; the wall the origin does see still faces it.
    const Scene s = sample_scene({{{0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.6, 0.6},
                                  {{0.8, 0, 0.4}, Vec3d::UnitY(), Vec3d::UnitZ(), 0.6, 0.3}},
                                 0.005, 0.001, 15);
    const GrowResult r = grow_surfaces(s.cloud, config_mm());
    ASSERT_EQ(r.stats.orientation, OrientationSource::kFrameOrigin);
    std::size_t floor = 0, wall = 0;
    for (const Surface& surf : r.surfaces) {
        if (std::abs(surf.normal.z()) > 0.9) {
            ++floor;
            EXPECT_GT(surf.normal.z(), 0.9) << "home " << surf.home.transpose();
        } else if (std::abs(surf.normal.x()) > 0.9) {
            ++wall;
            EXPECT_LT(surf.normal.x(), -0.9) << "home " << surf.home.transpose();
        }
    }
    EXPECT_GT(floor, 50u);
    EXPECT_GT(wall, 20u);
}

TEST(SurfaceGrower, RangeBandsCountEveryValidPoint) {
    Scene s =
        sample_scene({{{0.5, 0, 0}, Vec3d::UnitY(), Vec3d::UnitZ(), 0.3, 0.3}}, 0.005, 0.0, 13);
    const Scene far =
        sample_scene({{{2.5, 0, 0}, Vec3d::UnitY(), Vec3d::UnitZ(), 0.3, 0.3}}, 0.005, 0.0, 14);
    s.cloud.points.insert(s.cloud.points.end(), far.cloud.points.begin(), far.cloud.points.end());
    GrowerConfig cfg = config_mm();
    cfg.viewpoint = Vec3d::Zero();
    const GrowResult r = grow_surfaces(s.cloud, cfg);
    ASSERT_TRUE(r.stats.range_known);
    std::uint64_t points = 0, registered = 0;
    for (const RangeBand& b : r.stats.range_bands) {
        points += b.points;
        registered += b.registered;
    }
    EXPECT_EQ(points, r.stats.valid_points);
    EXPECT_EQ(registered, r.stats.registered);
    ASSERT_GE(r.stats.range_bands.size(), 3u);
    EXPECT_GT(r.stats.range_bands[0].points, 0u);  // 0.5 m plane
    EXPECT_EQ(r.stats.range_bands[1].points, 0u);
    EXPECT_GT(r.stats.range_bands[2].points, 0u);  // 2.5 m plane
}

// A mu beyond the whole cloud is a wrong unit or a typo: refused before minutes of work, whatever
// its size (1e40 once overflowed into a wrong message); a mu within the cloud's extent is not.
TEST(SurfaceGrower, MuBeyondTheWholeCloudIsRefused) {
    // Coarse: a mu near the whole cloud makes every neighbourhood the whole cloud (N^2 work).
    const Scene s =
        sample_scene({{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15}}, 0.01, 0.0, 1);
    Aabb box;
    for (const Vec3f& p : s.cloud.points) box.add(p.cast<double>());
    const double diagonal = box.size().norm();
    for (const double mu : {1.01 * diagonal, 1e3, 1e30}) {
        GrowerConfig cfg = config_mm();
        cfg.mu = mu;
        try {
            (void)grow_surfaces(s.cloud, cfg);
            ADD_FAILURE() << "accepted mu = " << mu;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << mu;
            EXPECT_NE(std::string(e.what()).find("larger than the whole cloud"), std::string::npos)
                << e.what();
        }
    }
    GrowerConfig cfg = config_mm();
    cfg.mu = 0.9 * diagonal;
    EXPECT_NO_THROW((void)grow_surfaces(s.cloud, cfg));
}

// Lengths the cloud's float coordinates cannot express are refused by name, whatever else is
// set; so are a mu finer than the coordinates resolve, absurd counts and angles. The rules live
// here, so the CLI and Python get the same answers.
TEST(SurfaceGrower, AbsurdParametersAreRefusedByName) {
    const Scene s =
        sample_scene({{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15}}, 0.004, 0.0, 1);
    auto message = [&](auto set) -> std::string {
        GrowerConfig cfg = config_mm();
        set(cfg);
        try {
            (void)grow_surfaces(s.cloud, cfg);
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << e.what();
            return e.what();
        }
        return "accepted";
    };
    const std::pair<std::string, std::function<void(GrowerConfig&)>> cases[] = {
        {"mu = 1e+40 is beyond the range of float coordinates", [](auto& c) { c.mu = 1e40; }},
        {"mu = nan is not a finite length", [](auto& c) { c.mu = std::nan(""); }},
        {"range band = 1e-300 is below the smallest length",
         [](auto& c) { c.range_band = 1e-300; }},
        {"plane tolerance = inf", [](auto& c) { c.plane_tolerance = INFINITY; }},
        {"pool radius = 1e+39", [](auto& c) { c.pool_radius = 1e39; }},
        {"crop radius = 1e+300", [](auto& c) { c.crop.radius = 1e300; }},
        {"crop box corner = -1e+39",
         [](auto& c) {
             c.crop.box = Aabb{Vec3d(-1e39, 0, 0), Vec3d(1, 1, 1)};
         }},
        {"viewpoint = 1e+300", [](auto& c) { c.viewpoint = Vec3d(1e300, 0, 0); }},
        {"crop centre = nan",
         [](auto& c) {
             c.crop.radius = 1;
             c.crop.center = Vec3d(0, std::nan(""), 0);
         }},
        {"mu = 1e-09 is finer than the cloud's float coordinates resolve",
         [](auto& c) { c.mu = 1e-9; }},
        {"min-pts must be at most 100000", [](auto& c) { c.min_pts = kMaxMinPts + 1; }},
        {"pool-angle must lie in [0, 90)", [](auto& c) { c.pool_angle_deg = 90; }},
        {"pool-angle must lie in [0, 90)", [](auto& c) { c.pool_angle_deg = std::nan(""); }},
        {"pool radius must be a length >= 0", [](auto& c) { c.pool_radius = -1; }},
    };
    for (const auto& [expected, set] : cases)
        EXPECT_NE(message(set).find(expected), std::string::npos)
            << expected << ": " << message(set);
    // Within the float range and the cloud, huge lengths are computed, not refused.
    EXPECT_EQ(message([](auto& c) {
                  c.range_band = 1e38;
                  c.crop.radius = 1e38;
                  c.viewpoint = Vec3d(1e38, 0, 0);
                  c.plane_tolerance = 1e38;
              }),
              "accepted");
    EXPECT_EQ(message([](auto& c) { c.min_pts = kMaxMinPts; }), "accepted");
}

// Two lattice clusters `apart` on each axis, far from the frame origin (normals face +z by rule,
// as in a georeferenced survey, wherever the clusters are).
PointCloud two_clusters(double step, double apart) {
    PointCloud c;
    test::lattice_patches(step, Vec3d::Zero(), 1, c.points);
    test::lattice_patches(step, Vec3d::Constant(apart), 2, c.points);
    c.offset = Vec3d::Constant(1e9);
    return c;
}

// Clusters 1e6 m and 1e7 m apart need more than 63 bits of grid keys (ranked cubes). They grow as
// the same clusters 100 cubes apart: exactly at the index origin, where every position, cube
// border and sum is the same float in both clouds (lattice steps of the float resolution at
// 1e6 and 1e7 m, cubes of whole steps). The far cluster's arithmetic rounds at that resolution
// (1/16 m, 1 m), so there the same homes grow, with normals within a degree.
TEST(SurfaceGrower, ClustersFarApartGrowAsWhenNear) {
    struct Case {
        double step, side, apart;
    };
    for (const Case& k : {Case{1.0 / 16, 0.25, 1e6}, Case{1.0, 4.0, 1e7}}) {
        SCOPED_TRACE(k.apart);
        GrowerConfig cfg;
        cfg.mu = test::mu_for_cube_side(k.side);
        cfg.threads = 2;
        const double near_apart = 100 * k.side;
        const PointCloud far = two_clusters(k.step, k.apart),
                         near = two_clusters(k.step, near_apart);
        ASSERT_TRUE(CubeIndex(far.points, cfg.mu).ranked());
        ASSERT_FALSE(CubeIndex(near.points, cfg.mu).ranked());
        const GrowResult a = grow_surfaces(far, cfg), b = grow_surfaces(near, cfg);
        check_invariants(far, cfg, a);
        const std::size_t half = far.size() / 2;
        EXPECT_TRUE(std::equal(a.labels.begin(), a.labels.begin() + std::ptrdiff_t(half),
                               b.labels.begin()));
        EXPECT_EQ(a.stats.registered, b.stats.registered);
        ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
        EXPECT_GE(a.surfaces.size(), 6u);
        for (std::size_t i = 0; i < a.surfaces.size(); ++i) {
            const Surface &sa = a.surfaces[i], &sb = b.surfaces[i];
            const bool second = sa.home.x() > k.apart / 2;
            EXPECT_EQ(sa.home - Vec3d::Constant(second ? k.apart - near_apart : 0.0), sb.home);
            EXPECT_LT(axis_angle_between(sa.normal, sb.normal), 1 * kDeg) << i;
            if (second) continue;
            EXPECT_EQ(sa.centroid, sb.centroid) << i;
            EXPECT_EQ(sa.normal, sb.normal) << i;
            EXPECT_EQ(sa.eigenvalues, sb.eigenvalues) << i;
            EXPECT_EQ(sa.radius, sb.radius) << i;
            EXPECT_EQ(sa.neighbours, sb.neighbours) << i;
            EXPECT_EQ(sa.point_count, sb.point_count) << i;
            EXPECT_EQ(sa.tolerance, sb.tolerance) << i;
        }
    }
}

// More threads than a machine can use are clamped (100000 once crashed with SIGSEGV), and the
// result does not change.
TEST(SurfaceGrower, AbsurdThreadCountsAreClamped) {
    EXPECT_GE(max_threads(), kThreadsPerCore);
    EXPECT_EQ(resolve_threads(1), 1);
    EXPECT_EQ(resolve_threads(1000000), max_threads());
    EXPECT_LE(resolve_threads(0), max_threads());
    const Scene s =
        sample_scene({{{0, 0, 0.5}, Vec3d::UnitX(), Vec3d::UnitY(), 0.2, 0.15}}, 0.004, 0.001, 2);
    GrowerConfig cfg = config_mm();
    cfg.threads = 1;
    const GrowResult one = grow_surfaces(s.cloud, cfg);
    cfg.threads = 1000000;
    const GrowResult many = grow_surfaces(s.cloud, cfg);
    EXPECT_EQ(many.labels, one.labels);
    ASSERT_EQ(many.surfaces.size(), one.surfaces.size());
}

TEST(SurfaceGrower, RejectsParametersOutOfRange) {
    auto expect_invalid = [](GrowerConfig c, const char* what) {
        try {
            const SurfaceGrower g(c);
            ADD_FAILURE() << "accepted " << what;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter) << what;
        }
    };
    GrowerConfig c;
    c.mu = 0;
    expect_invalid(c, "mu = 0");
    c.mu = -0.01;
    expect_invalid(c, "mu < 0");
    c.mu = std::nan("");
    expect_invalid(c, "mu = NaN");
    c = {};
    c.min_pts = 2;
    expect_invalid(c, "min_pts = 2");
    c = {};
    c.alpha = 1.0;
    expect_invalid(c, "alpha = 1");
    c.alpha = 0.5;
    expect_invalid(c, "alpha < 1");
    c = {};
    c.plane_tolerance = -1;
    expect_invalid(c, "negative tolerance");
    c = {};
    c.adaptive_factor = 0.5;
    expect_invalid(c, "adaptive radius below mu");
    c.adaptive_factor = 100;
    expect_invalid(c, "adaptive radius above 64 mu");
    c = {};
    c.threads = -1;
    expect_invalid(c, "threads < 0");
    c = {};
    c.crop.radius = 0;
    expect_invalid(c, "crop radius 0");
}

}  // namespace
}  // namespace surfgrow
