#include "surfgrow/render/renderer.hpp"

#include <omp.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/memory_budget.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/render/overlay.hpp"
#include "surfgrow/render/raster.hpp"
#include "surfgrow/render/tiles.hpp"

namespace surfgrow::render {

namespace {

constexpr int kMinSide = 16;
constexpr int kMaxSide = 16384;
constexpr double kMaxPixels = 64.0 * 1024 * 1024;
constexpr int kTile = 64;  // pixels: a tile's samples (and depths) stay in cache

double sq(double x) {
    return x * x;
}

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorCode::kInvalidParameter, message);
}

void check_range(const char* name, double value, double lo, double hi) {
    if (!(value >= lo && value <= hi))
        invalid(cat({"render option ", name, " must be in [", num(lo), ", ", num(hi), "], got ",
                     num(value)}));
}

// A box in camera coordinates (along right, up, forward), in world units.
struct Extent {
    double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL, z0 = HUGE_VAL,
           z1 = -HUGE_VAL;
    void add(const Vec3d& c, const Vec3d& half) {
        x0 = std::min(x0, c.x() - half.x()), x1 = std::max(x1, c.x() + half.x());
        y0 = std::min(y0, c.y() - half.y()), y1 = std::max(y1, c.y() + half.y());
        z0 = std::min(z0, c.z() - half.z()), z1 = std::max(z1, c.z() + half.z());
    }
    [[nodiscard]] bool empty() const { return !(x0 <= x1); }
};

Vec3d axes_of(const Camera& cam, const Vec3d& p) {
    return {p.dot(cam.right()), p.dot(cam.up()), p.dot(cam.forward())};
}

// Exact box of a disk along the camera axes: a circle of radius r with unit normal n reaches
// r * sqrt(1 - (n . e)^2) along a unit direction e.
Vec3d disk_half_extent(const Camera& cam, const Vec3d& n, double r) {
    auto reach = [&](const Vec3d& e) { return r * std::sqrt(std::max(0.0, 1 - sq(n.dot(e)))); };
    return {reach(cam.right()), reach(cam.up()), reach(cam.forward())};
}

// Stray far points must not shrink the picture: frame the disks in `framed`, the lines of no
// disk, those of framed disks when every normal is drawn (else they are drawn only where disks
// are big on screen, which depends on the framing), and the points only when there is nothing
// else.
Extent scene_extent(const Scene& scene, const Camera& cam, const std::vector<std::uint8_t>& framed,
                    bool disk_lines) {
    Extent e;
    for (std::size_t i = 0; i < scene.disks.size(); ++i) {
        const Disk& d = scene.disks[i];
        if (!framed[i]) continue;
        e.add(axes_of(cam, d.center), disk_half_extent(cam, d.normal.normalized(), d.radius));
    }
    for (const Segment& s : scene.lines) {
        if (!s.from.allFinite() || !s.to.allFinite()) continue;
        if (s.disk >= 0 && (!disk_lines || static_cast<std::size_t>(s.disk) >= framed.size() ||
                            !framed[static_cast<std::size_t>(s.disk)]))
            continue;
        e.add(axes_of(cam, s.from), Vec3d::Zero());
        e.add(axes_of(cam, s.to), Vec3d::Zero());
    }
    if (e.empty())
        for (const ScenePoint& p : scene.points)
            if (is_finite(p.position))
                e.add(axes_of(cam, p.position.cast<double>()), Vec3d::Zero());
    return e;
}

// Disks a close-up draws: those near its centre. All usable disks without one.
std::vector<std::uint8_t> drawn_disks(const Scene& scene, const RenderOptions& options) {
    std::vector<std::uint8_t> drawn(scene.disks.size(), 0);
    for (std::size_t i = 0; i < scene.disks.size(); ++i)
        drawn[i] =
            usable(scene.disks[i]) &&
            (!options.close_up || (scene.disks[i].center - options.close_up->center).norm() <=
                                      kCloseUpReach * options.close_up->half_size);
    return drawn;
}

}  // namespace

void validate(const RenderOptions& o) {
    if (o.width < kMinSide || o.width > kMaxSide || o.height < kMinSide || o.height > kMaxSide ||
        double(o.width) * o.height > kMaxPixels)
        invalid(cat({"image size must be ", num(kMinSide), " to ", num(kMaxSide),
                     " pixels a side and at most 64 Mpixel, got ", num(o.width), " x ",
                     num(o.height)}));
    check_range("supersample", o.supersample, 1, 4);
    // Any count: resolve_threads clamps it to what the machine can use, as for every stage.
    check_range("threads", o.threads, 0, std::numeric_limits<int>::max());
    check_range("margin", o.margin, 0, 0.4);
    check_range("point_size", o.point_size, 0.1, 64);
    check_range("line_width", o.line_width, 0.1, 64);
    check_range("normal_min_radius", o.normal_min_radius, 0, 1e6);
    if (o.close_up && (!o.close_up->center.allFinite() || !o.close_up->forward.allFinite() ||
                       o.close_up->forward.norm() == 0 || !(o.close_up->half_size > 0) ||
                       !std::isfinite(o.close_up->half_size)))
        invalid(
            "render option close_up needs a finite centre, a non-zero direction and a size > 0");
    check_range("min_disk_thickness", o.min_disk_thickness, 0, 16);
    check_range("rim_shade", o.rim_shade, 0, 1);
    check_range("lighting.ambient", o.lighting.ambient, 0, 2);
    check_range("lighting.diffuse", o.lighting.diffuse, 0, 2);
    check_range("lighting.fog", o.lighting.fog, 0, 1);
    if (!o.lighting.direction.allFinite() || o.lighting.direction.norm() == 0)
        invalid("render option lighting.direction must be a finite non-zero vector");
}

Camera frame_scene(const Scene& scene, const RenderOptions& options) {
    validate(options);
    if (options.camera) return *options.camera;
    const int band = overlay_layout(options, !scene.legend.empty()).band_height;
    const PixelRect rect{0, 0, double(options.width), double(options.height - band)};
    const double margin = options.margin * std::min(options.width, options.height);
    if (options.close_up) {
        const CloseUp& c = *options.close_up;
        Camera cam = Camera::looking(c.forward, Vec3d::UnitZ());
        const Vec3d a = axes_of(cam, c.center);
        cam.fit(a.x() - c.half_size, a.x() + c.half_size, a.y() - c.half_size, a.y() + c.half_size,
                rect, margin);
        return cam;
    }
    Camera cam = Camera::preset(options.view);
    const std::vector<std::uint8_t> framed =
        options.framing == Framing::kBulk ? bulk_disks(scene.disks) : drawn_disks(scene, options);
    const Extent e = scene_extent(scene, cam, framed, options.normal_min_radius == 0);
    if (e.empty())
        cam.fit(-1, 1, -1, 1, rect, margin);
    else
        cam.fit(e.x0, e.x1, e.y0, e.y1, rect, margin);
    return cam;
}

Rgb shade(Rgb color, const Vec3d& normal, const Camera& camera, const Lighting& lighting) {
    Vec3d n = camera.to_camera(normal.normalized());
    if (n.z() < 0) n = -n;  // two-sided: light the side the viewer sees
    const double lambert = std::max(0.0, n.dot(lighting.direction.normalized()));
    return scaled(color, lighting.ambient + lighting.diffuse * lambert);
}

Image render_scene(const Scene& scene, const RenderOptions& options) {
    const Camera cam = frame_scene(scene, options);  // validates
    // What drawing holds at once: per disk its ellipse, tile bins and framing grid (about 250
    // bytes with the scene's own), per point 40, per normal 120, the image and one tile raster
    // per thread. Checked before anything big is allocated: a clear error beats an OOM kill.
    check_memory(250.0 * double(scene.disks.size()) + 40.0 * double(scene.points.size()) +
                     120.0 * double(scene.lines.size()) +
                     3.0 * double(options.width) * double(options.height),
                 cat({"drawing ", std::to_string(scene.disks.size()), " disks and ",
                      std::to_string(scene.points.size()), " points"}));
    const double scale = cam.scale();
    const Vec3d& f = cam.forward();

    // Which disks face the viewer; points and normals follow their disk.
    enum Facing : std::uint8_t { kSkip, kFront, kBack };
    std::vector<std::uint8_t> facing(scene.disks.size(), kSkip);
    Extent depth;  // of the disk centres, for the fog
    const std::vector<std::uint8_t> drawn = drawn_disks(scene, options);
    for (std::size_t i = 0; i < scene.disks.size(); ++i) {
        const Disk& d = scene.disks[i];
        if (!drawn[i]) continue;
        facing[i] = d.normal.dot(f) > 0 ? kBack : kFront;
        depth.add(axes_of(cam, d.center), Vec3d::Zero());
    }
    // Depths are stored as float relative to the middle of the scene, so that a scene far from
    // the origin keeps its depth resolution.
    double z_ref = depth.empty() ? 0.0 : (depth.z0 + depth.z1) / 2;
    if (depth.empty())
        for (const ScenePoint& p : scene.points)
            if (is_finite(p.position)) {
                z_ref = p.position.cast<double>().dot(f);
                break;
            }
    // Points and normals of a disk seen from behind are left out unless back faces are shown:
    // ghosted, they would only cloud the view through it.
    auto shown = [&](std::int32_t disk) {
        const auto k = static_cast<std::size_t>(disk);
        if (disk < 0 || k >= facing.size()) return !options.close_up;
        if (facing[k] == kSkip) return !options.close_up;
        return options.back_faces == BackFaces::kShow || facing[k] != kBack;
    };

    auto ellipse_of = [&](const Disk& d, bool ghost) {
        const Vec3d n = d.normal.normalized();
        // u: the in-plane direction square to the view, drawn at full length (major axis);
        // v: the other in-plane direction, foreshortened by |n . f| (minor axis).
        Vec3d u = n.cross(f);
        if (u.norm() < 1e-9) u = cam.right() - n * n.dot(cam.right());
        u.normalize();
        const Vec3d v = n.cross(u);
        const Vec3d c = cam.project(d.center);
        ScreenEllipse e;
        e.cx = c.x(), e.cy = c.y(), e.depth = c.z() - z_ref;
        const double sx = u.dot(cam.right()), sy = -u.dot(cam.up());
        const double slen = std::hypot(sx, sy);
        e.ux = sx / slen, e.uy = sy / slen;
        e.a = d.radius * scale;
        e.b = std::max(e.a * std::abs(n.dot(f)), options.min_disk_thickness / 2);
        // Which way v runs along the minor axis (-uy, ux) decides the sign of the depth slope.
        const double along = -e.uy * v.dot(cam.right()) - e.ux * v.dot(cam.up());
        e.depth_b = (along >= 0 ? 1.0 : -1.0) * d.radius * v.dot(f);
        Rgb lit = shade(d.color, n, cam, options.lighting);
        if (depth.z1 > depth.z0)
            lit = mix(lit, options.background,
                      options.lighting.fog * (c.z() - depth.z0) / (depth.z1 - depth.z0));
        if (ghost) lit = mix(lit, options.background, 0.3);
        e.fill = lit;
        e.rim = scaled(lit, options.rim_shade);
        // A ring about one pixel wide, on disks big enough to show one.
        e.rim_start = e.a >= 3 && options.rim_shade < 1 ? sq(1 - 1.0 / e.a) : 2.0;
        return e;
    };
    std::vector<ScreenEllipse> solid, ghost;
    for (std::size_t i = 0; i < scene.disks.size(); ++i) {
        if (facing[i] == kFront || (facing[i] == kBack && options.back_faces == BackFaces::kShow))
            solid.push_back(ellipse_of(scene.disks[i], false));
        else if (facing[i] == kBack && options.back_faces == BackFaces::kGhost)
            ghost.push_back(ellipse_of(scene.disks[i], true));
    }
    struct Line {
        Vec3d a, b;  // projected, depth lifted
        Rgb color;
    };
    std::vector<Line> lines;
    // Normals start on their disk: lift them about two pixels towards the viewer.
    const double lift = 2 / scale + z_ref;
    // A disk's normal only where the disk is big enough on screen for it to mean something.
    auto big_enough = [&](std::int32_t disk) {
        const auto k = static_cast<std::size_t>(disk);
        return disk < 0 || k >= scene.disks.size() ||
               scene.disks[k].radius * scale >= options.normal_min_radius;
    };
    for (const Segment& s : scene.lines)
        if (shown(s.disk) && big_enough(s.disk) && s.from.allFinite() && s.to.allFinite())
            lines.push_back({cam.project(s.from) - Vec3d(0, 0, lift),
                             cam.project(s.to) - Vec3d(0, 0, lift), s.color});

    // Tiles: each needs what touches it and its apron (the outline looks about half a pixel
    // past the tile's edge).
    const int ss = options.supersample;
    const int apron = (ss + 1) / 2;
    const TileGrid grid(options.width, options.height, kTile);
    const int threads = resolve_threads(options.threads);
    const double pad = 1.0 + double(apron) / ss;
    const double point_radius = options.point_size / 2;
    const double half_line = options.line_width / 2;
    auto ellipse_box = [](const std::vector<ScreenEllipse>& list) {
        return [&list](std::size_t i, double& x0, double& y0, double& x1, double& y1) {
            const ScreenEllipse& e = list[i];
            const double hw = e.half_width(), hh = e.half_height();
            x0 = e.cx - hw, x1 = e.cx + hw, y0 = e.cy - hh, y1 = e.cy + hh;
            return true;
        };
    };
    const Bins solid_bins = grid.bin(solid.size(), ellipse_box(solid), pad);
    const Bins ghost_bins = grid.bin(ghost.size(), ellipse_box(ghost), pad);
    // Points are projected once (x, y, depth with the bias); NaN x marks one not drawn.
    std::vector<Eigen::Vector3f> dots(scene.points.size());
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < scene.points.size(); ++i) {
        const ScenePoint& p = scene.points[i];
        if (!shown(p.disk) || !is_finite(p.position)) {
            dots[i].x() = std::numeric_limits<float>::quiet_NaN();
            continue;
        }
        const Vec3d q = cam.project(p.position.cast<double>());
        dots[i] = Vec3d(q.x(), q.y(), q.z() - z_ref + scene.point_depth_bias).cast<float>();
    }
    const Bins point_bins = grid.bin(
        dots.size(),
        [&](std::size_t i, double& x0, double& y0, double& x1, double& y1) {
            const double x = dots[i].x(), y = dots[i].y();
            x0 = x - point_radius, x1 = x + point_radius;
            y0 = y - point_radius, y1 = y + point_radius;
            return !std::isnan(x);
        },
        pad);
    const Bins line_bins = grid.bin(
        lines.size(),
        [&](std::size_t i, double& x0, double& y0, double& x1, double& y1) {
            const Line& l = lines[i];
            x0 = std::min(l.a.x(), l.b.x()) - half_line,
            x1 = std::max(l.a.x(), l.b.x()) + half_line;
            y0 = std::min(l.a.y(), l.b.y()) - half_line,
            y1 = std::max(l.a.y(), l.b.y()) + half_line;
            return true;
        },
        pad);

    const double r_mid = median_disk_radius(scene.disks);
    const bool outlines = options.outlines && r_mid > 0;
    const double outline_step = std::max(3 * r_mid, 4 / scale);
    Image image(options.width, options.height);
    // One raster per thread, sized up front: nothing allocates (or throws) in the parallel loop.
    std::vector<Raster> rasters(static_cast<std::size_t>(threads), Raster(ss, apron));
    for (Raster& r : rasters) r.reset(0, 0, kTile, kTile, options.background);

#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (int t = 0; t < grid.count(); ++t) {
        Raster& raster = rasters[static_cast<std::size_t>(omp_get_thread_num())];
        raster.reset(grid.x0(t), grid.y0(t), grid.width(t), grid.height(t), options.background);
        // Solid disks, their outlines, then the see-through ones (which must neither cast
        // outlines nor get them), then points and normals.
        for (std::uint32_t i : solid_bins.of(t)) raster.fill_ellipse(solid[i]);
        if (outlines) raster.outline(outline_step, {30, 30, 30}, 0.6);
        raster.set_ghost(true);
        for (std::uint32_t i : ghost_bins.of(t)) raster.fill_ellipse(ghost[i]);
        raster.set_ghost(false);
        for (std::uint32_t i : point_bins.of(t))
            raster.fill_dot(double(dots[i].x()), double(dots[i].y()), double(dots[i].z()),
                            point_radius, scene.points[i].color);
        for (std::uint32_t i : line_bins.of(t)) {
            const Line& l = lines[i];
            raster.draw_segment(l.a.x(), l.a.y(), l.a.z(), l.b.x(), l.b.y(), l.b.z(), half_line,
                                l.color);
        }
        raster.resolve_into(image);
    }

    draw_overlays(image, scene.legend, cam, options);
    return image;
}

}  // namespace surfgrow::render
