// What pictures are framed on (bulk_disks), the colours of bound planes (group_colors) and the
// corner a close-up shows (find_corner), on scenes with known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "surfgrow/core/error.hpp"
#include "surfgrow/render/close_up.hpp"
#include "surfgrow/render/framing.hpp"
#include "surfgrow/render/group_colors.hpp"
#include "surfgrow/render/renderer.hpp"

namespace surfgrow::render {
namespace {

constexpr double kR = 0.012;  // disk radius, mu = 12 mm

// Disks on a grid of pitch `step` over the rectangle origin + [0, a] u + [0, b] v.
void add_plate(std::vector<Disk>& disks, const Vec3d& origin, const Vec3d& u, const Vec3d& v,
               double a, double b, double step, const Vec3d& normal) {
    for (double s = 0; s <= a + 1e-9; s += step)
        for (double t = 0; t <= b + 1e-9; t += step)
            disks.push_back({origin + s * u + t * v, normal, kR, {}});
}

// A 1 m x 1 m plate at z = 2 and two sparse strips on the floor 2 m below it (2 % of the disks).
std::vector<Disk> plate_with_floor_strips() {
    std::vector<Disk> d;
    add_plate(d, {0, 0, 2}, Vec3d::UnitX(), Vec3d::UnitY(), 1, 1, 0.012, -Vec3d::UnitZ());
    const std::size_t plate = d.size();
    for (int k = 0; k < 2; ++k)
        for (std::size_t i = 0; i < plate / 100; ++i)
            d.push_back(
                {Vec3d(-1 + 0.1 * double(i % 30), -2 + 5.0 * k, 0), Vec3d::UnitZ(), 4 * kR, {}});
    return d;
}

TEST(BulkDisks, FramesThePlateNotTheFloorStripsBelowIt) {
    const std::vector<Disk> d = plate_with_floor_strips();
    const std::vector<std::uint8_t> bulk = bulk_disks(d);
    ASSERT_EQ(bulk.size(), d.size());
    std::size_t plate = 0, strips = 0;
    for (std::size_t i = 0; i < d.size(); ++i) (d[i].center.z() > 1 ? plate : strips) += bulk[i];
    EXPECT_EQ(plate, 84u * 84u);  // every plate disk
    EXPECT_EQ(strips, 0u);
}

TEST(BulkDisks, FramedPictureIsFilledByThePlate) {
    const std::vector<Disk> d = plate_with_floor_strips();
    Scene scene;
    scene.disks = d;
    RenderOptions options;
    options.view = View::kTop;
    options.legend = false;
    const Camera bulk = frame_scene(scene, options);
    options.framing = Framing::kAll;
    const Camera all = frame_scene(scene, options);
    // The plate spans most of the picture's height when framed on the bulk; with everything
    // framed (strips 5 m apart) well under half of it.
    const double plate_px_bulk = bulk.scale() * 1.0, plate_px_all = all.scale() * 1.0;
    EXPECT_GT(plate_px_bulk, 0.85 * options.height);
    EXPECT_LT(plate_px_all, 0.3 * options.height);
}

TEST(BulkDisks, FarEndsOfOneStructureStayAndManySmallPiecesAreFramedAlmostWhole) {
    // A plate and, a little beyond its edge (10 cm: more than the link distance), a sparser end.
    std::vector<Disk> d;
    add_plate(d, {0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 1, 1, 0.012, Vec3d::UnitZ());
    const std::size_t plate = d.size();
    add_plate(d, {1.1, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.3, 1, 0.05, Vec3d::UnitZ());
    std::vector<std::uint8_t> bulk = bulk_disks(d);
    for (std::size_t i = plate; i < d.size(); ++i) ASSERT_EQ(bulk[i], 1) << i;

    // 50 equal pieces 1 m apart: none holds 5 %, the largest down to 80 % are taken.
    d.clear();
    for (int k = 0; k < 50; ++k)
        add_plate(d, {2.0 * k, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.1, 0.1, 0.012,
                  Vec3d::UnitZ());
    bulk = bulk_disks(d);
    std::size_t taken = 0;
    for (const std::uint8_t b : bulk) taken += b;
    EXPECT_GE(double(taken), 0.8 * double(d.size()));
}

TEST(BulkDisks, UnusableAndAbsurdDisksAreLeftOutWithoutHarm) {
    std::vector<Disk> d;
    add_plate(d, {0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 0.5, 0.5, 0.012, Vec3d::UnitZ());
    d.push_back({Vec3d(1e300, -1e300, 0), Vec3d::UnitZ(), kR, {}});
    d.push_back({Vec3d(NAN, 0, 0), Vec3d::UnitZ(), kR, {}});
    d.push_back({Vec3d(0, 0, 0), Vec3d::UnitZ(), 0.0, {}});
    d.push_back({Vec3d(0, 0, 0), Vec3d::Zero(), kR, {}});
    const std::vector<std::uint8_t> bulk = bulk_disks(d);
    for (std::size_t i = d.size() - 4; i < d.size(); ++i) EXPECT_EQ(bulk[i], 0) << i;
    EXPECT_EQ(bulk[0], 1);
    EXPECT_TRUE(bulk_disks({}).empty());
    EXPECT_EQ(parse_framing("all"), Framing::kAll);
    EXPECT_THROW((void)parse_framing("most"), Error);
}

Surface surface_at(const Vec3d& p, const Vec3d& n) {
    Surface s;
    s.home = s.centroid = p;
    s.normal = n;
    s.radius = kR;
    return s;
}

TEST(GroupColors, FacesThatMeetDifferAndNearbyTreadsToo) {
    // A stair: treads (horizontal) and risers (vertical) alternating, each its own group; plus
    // surfaces of no group.
    std::vector<Surface> s;
    std::vector<std::int32_t> g;
    for (int step = 0; step < 6; ++step) {
        for (double x = 0; x <= 0.3; x += 0.012)
            for (double y = 0; y <= 0.6; y += 0.012) {
                s.push_back(surface_at({0.3 * step + x, y, 0.2 * step}, Vec3d::UnitZ()));
                g.push_back(2 * step);
            }
        for (double z = 0; z <= 0.2; z += 0.012)
            for (double y = 0; y <= 0.6; y += 0.012) {
                s.push_back(surface_at({0.3 * step + 0.3, y, 0.2 * step + z}, -Vec3d::UnitX()));
                g.push_back(2 * step + 1);
            }
    }
    s.push_back(surface_at({5, 5, 5}, Vec3d::UnitZ()));
    g.push_back(-1);
    const std::vector<Rgb> c = group_colors(s, g);
    ASSERT_EQ(c.size(), s.size());
    EXPECT_EQ(c.back(), kUnassignedGrey);
    std::vector<Rgb> of(12);
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
        of[static_cast<std::size_t>(g[i])] = c[i];
        EXPECT_TRUE(std::find(kGroupPalette.begin(), kGroupPalette.end(), c[i]) !=
                    kGroupPalette.end());
    }
    for (std::size_t k = 0; k + 1 < of.size(); ++k) {
        EXPECT_NE(of[k], of[k + 1]) << "faces " << k << " and " << k + 1 << " meet";
        if (k + 2 < of.size()) {
            EXPECT_NE(of[k], of[k + 2]) << "faces " << k << " and " << k + 2;
        }
    }
    // Eight colours for twelve faces: each is used.
    std::set<std::tuple<int, int, int>> distinct;
    for (const Rgb& x : of) distinct.insert({x.r, x.g, x.b});
    EXPECT_EQ(distinct.size(), 8u);
    EXPECT_EQ(group_colors(s, g), c);  // deterministic
    g.pop_back();
    EXPECT_THROW((void)group_colors(s, g), Error);
}

// The inside corner of a box: floor z = 0, walls x = 0 and y = 0, 1 m each, normals inwards.
std::vector<Disk> box_corner(std::vector<std::int32_t>& groups) {
    std::vector<Disk> d;
    add_plate(d, {0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitY(), 1, 1, 0.012, Vec3d::UnitZ());
    groups.assign(d.size(), 0);
    add_plate(d, {0, 0, 0}, Vec3d::UnitY(), Vec3d::UnitZ(), 1, 1, 0.012, Vec3d::UnitX());
    groups.resize(d.size(), 1);
    add_plate(d, {0, 0, 0}, Vec3d::UnitX(), Vec3d::UnitZ(), 1, 1, 0.012, Vec3d::UnitY());
    groups.resize(d.size(), 2);
    return d;
}

TEST(FindCorner, FindsWhereThreeFacesMeetAndLooksAtTheirFronts) {
    std::vector<std::int32_t> groups;
    std::vector<Disk> d = box_corner(groups);
    const auto c = find_corner(d, groups);
    ASSERT_TRUE(c.has_value());
    EXPECT_LT(c->center.norm(), 2 * kR) << c->center.transpose();
    EXPECT_NEAR(c->half_size, kCloseUpRadii * kR, 1e-12);
    // Looking against the faces' normals: each face is seen from its front.
    for (const Vec3d& n : {Vec3d(Vec3d::UnitX()), Vec3d(Vec3d::UnitY()), Vec3d(Vec3d::UnitZ())})
        EXPECT_LT(n.dot(c->forward), -0.5);

    // Two faces only (an edge): found on the line where they meet.
    std::vector<std::int32_t> two(groups);
    for (std::int32_t& g : two) g = g == 2 ? -1 : g;
    const auto e = find_corner(d, two);
    ASSERT_TRUE(e.has_value());
    EXPECT_LT(std::hypot(e->center.x(), e->center.z()), 2 * kR) << e->center.transpose();

    // One face, or groups that do not fit the disks: no corner.
    std::vector<std::int32_t> one(groups.size(), 0);
    EXPECT_FALSE(find_corner(d, one).has_value());
    EXPECT_FALSE(find_corner(d, std::vector<std::int32_t>(3, 0)).has_value());
}

TEST(FindCorner, CloseUpDrawsOnlyTheCorner) {
    std::vector<std::int32_t> groups;
    Scene scene;
    scene.disks = box_corner(groups);
    // A far disk right in front of the corner along the view: left out of the close-up.
    const auto c = find_corner(scene.disks, groups);
    ASSERT_TRUE(c.has_value());
    scene.disks.push_back(
        {c->center - 3 * c->half_size * c->forward, -c->forward, 1.0, {255, 0, 0}});
    RenderOptions options;
    options.width = 320, options.height = 240, options.legend = false, options.axes = false;
    options.close_up = c;
    const Image image = render_scene(scene, options);
    std::size_t red = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const Rgb p = image.at(x, y);
            red += p.r > 150 && p.g < 60 && p.b < 60;
        }
    EXPECT_LT(red, 50u);
    options.close_up->half_size = -1;
    EXPECT_THROW((void)render_scene(scene, options), Error);
}

}  // namespace
}  // namespace surfgrow::render
