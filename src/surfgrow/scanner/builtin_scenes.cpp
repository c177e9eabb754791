#include "surfgrow/scanner/builtin_scenes.hpp"

#include <algorithm>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

namespace {

void add_box(SceneDescription& s, std::string name, const Vec3d& lo, const Vec3d& hi) {
    s.primitives.push_back({std::move(name), Box::from_min_max(lo, hi)});
}

void add_cylinder(SceneDescription& s, std::string name, const Vec3d& base, const Vec3d& top,
                  double radius) {
    s.primitives.push_back({std::move(name), Cylinder{base, top, radius, true}});
}

void add_rectangle(SceneDescription& s, std::string name, const Vec3d& center, const Vec3d& u,
                   const Vec3d& v, double width, double height) {
    s.primitives.push_back({std::move(name), Rectangle{center, u, v, 0.5 * width, 0.5 * height}});
}

}  // namespace

SceneDescription ibeam_channel_scene(const IBeamChannelParams& p) {
    SceneDescription s;
    s.name = "ibeam-channel";
    const double hx = 0.5 * p.length_m;
    const double z0 = p.girder_bottom_z_m;
    const double z_top = z0 + p.depth_m;
    const double tf = p.flange_thickness_m;

    add_rectangle(s, "scaffold-floor", Vec3d(0, 0, 0), Vec3d::UnitX(), Vec3d::UnitY(),
                  p.length_m + 1.0, 6.0);
    add_box(s, "deck", Vec3d(-hx - 0.5, -1.5, z_top),
            Vec3d(hx + 0.5, 1.5, z_top + p.deck_thickness_m));

    for (const int side : {+1, -1}) {
        const std::string tag = side > 0 ? "left" : "right";
        const double yc = side * 0.5 * p.girder_spacing_m;
        const double hf = 0.5 * p.flange_width_m, hw = 0.5 * p.web_thickness_m;
        add_box(s, tag + "-bottom-flange", Vec3d(-hx, yc - hf, z0), Vec3d(hx, yc + hf, z0 + tf));
        add_box(s, tag + "-web", Vec3d(-hx, yc - hw, z0 + tf), Vec3d(hx, yc + hw, z_top - tf));
        add_box(s, tag + "-top-flange", Vec3d(-hx, yc - hf, z_top - tf), Vec3d(hx, yc + hf, z_top));

        // Inner face of the web (facing the channel) and the direction into the channel.
        const double y_face = yc - side * hw;
        const double into = -side;
        for (std::size_t k = 0; k < p.stiffener_x_m.size(); ++k) {
            const double x = p.stiffener_x_m[k], ht = 0.5 * p.stiffener_thickness_m;
            const double y_end = y_face + into * p.stiffener_width_m;
            add_box(s, cat({tag, "-stiffener-", std::to_string(k)}),
                    Vec3d(x - ht, std::min(y_face, y_end), z0 + tf),
                    Vec3d(x + ht, std::max(y_face, y_end), z_top - tf));
        }

        const double zc = z0 + 0.5 * p.depth_m;
        const double y_plate = y_face + into * p.splice_thickness_m;
        add_box(s, tag + "-web-splice",
                Vec3d(-0.5 * p.splice_length_m, std::min(y_face, y_plate),
                      zc - 0.5 * p.splice_height_m),
                Vec3d(0.5 * p.splice_length_m, std::max(y_face, y_plate),
                      zc + 0.5 * p.splice_height_m));
        // 3 columns x 4 rows of bolt heads on the splice plate.
        int bolt = 0;
        for (const double bx : {-0.12, 0.0, 0.12}) {
            for (const double bz : {-0.2, -0.2 / 3, 0.2 / 3, 0.2}) {
                const Vec3d base(bx, y_plate, zc + bz);
                add_cylinder(s, cat({tag, "-bolt-", std::to_string(bolt++)}), base,
                             base + Vec3d(0, into * p.bolt_head_m, 0), p.bolt_radius_m);
            }
        }
    }
    s.scanner.home =
        pose_from_xyz_rpy(Vec3d(0, 0, p.scanner_height_m), Vec3d(0, deg_to_rad(-90.0), 0));
    s.scanner.step_m = Vec3d(0.5, 0, 0);
    return s;
}

SceneDescription room_corner_scene() {
    SceneDescription s;
    s.name = "room-corner";
    add_rectangle(s, "floor", Vec3d(0.75, 0.75, 0), Vec3d::UnitX(), Vec3d::UnitY(), 2.5, 2.5);
    add_rectangle(s, "wall-x", Vec3d(1.5, 0.75, 1.25), Vec3d::UnitZ(), Vec3d::UnitY(), 2.5, 2.5);
    add_rectangle(s, "wall-y", Vec3d(0.75, 1.5, 1.25), Vec3d::UnitX(), Vec3d::UnitZ(), 2.5, 2.5);
    s.scanner.home = pose_from_xyz_rpy(Vec3d(0.5, 0.5, 0.6), Vec3d(0, 0, deg_to_rad(45.0)));
    s.scanner.step_m = Vec3d(0.25, -0.25, 0);
    return s;
}

SceneDescription pipes_scene() {
    SceneDescription s;
    s.name = "pipes";
    const double wall_x = 1.2;
    add_rectangle(s, "floor", Vec3d(0.5, 0, 0), Vec3d::UnitX(), Vec3d::UnitY(), 2.0, 4.0);
    add_rectangle(s, "wall", Vec3d(wall_x, 0, 1.25), Vec3d::UnitZ(), Vec3d::UnitY(), 2.5, 4.0);
    struct Pipe {
        double x, z, r;
    };
    const Pipe pipes[] = {{0.90, 0.45, 0.08}, {0.95, 0.85, 0.05}, {0.85, 1.30, 0.15}};
    for (int i = 0; i < 3; ++i) {
        const Pipe& q = pipes[i];
        add_cylinder(s, cat({"pipe-", std::to_string(i)}), Vec3d(q.x, -1.8, q.z),
                     Vec3d(q.x, 1.8, q.z), q.r);
        for (const double yb : {-0.9, 0.9}) {
            add_box(s, cat({"bracket-", std::to_string(i), yb < 0 ? "-a" : "-b"}),
                    Vec3d(q.x, yb - 0.03, q.z - q.r - 0.012), Vec3d(wall_x, yb + 0.03, q.z - q.r));
        }
    }
    add_cylinder(s, "pipe-flange", Vec3d(0.85, 0.30, 1.30), Vec3d(0.85, 0.33, 1.30), 0.22);
    add_cylinder(s, "riser", Vec3d(0.55, -0.45, 0.0), Vec3d(0.55, -0.45, 2.0), 0.06);
    add_box(s, "valve-body", Vec3d(0.80, 0.40, 0.37), Vec3d(0.98, 0.55, 0.53));
    s.scanner.home = pose_from_xyz_rpy(Vec3d(0, 0, 0.9), Vec3d::Zero());
    s.scanner.step_m = Vec3d(0, 0.5, 0);
    return s;
}

SceneDescription corridor_scene() {
    SceneDescription s;
    s.name = "corridor";
    // The scanner looks along the corridor with its tilt axis across it, so at pan +-90 deg the
    // beam lies along the axis and every tilt position meets the side walls at one spot (the
    // tilt axis's poles, 1 m away); the end wall stands 3.5 m ahead, near the URG's 4 m limit.
    const double half_w = 1.0, h = 2.5, x_back = -1.5, x_end = 3.5;
    const double len = x_end - x_back, xc = 0.5 * (x_back + x_end);
    add_rectangle(s, "floor", Vec3d(xc, 0, 0), Vec3d::UnitX(), Vec3d::UnitY(), len, 2 * half_w);
    add_rectangle(s, "ceiling", Vec3d(xc, 0, h), Vec3d::UnitX(), Vec3d::UnitY(), len, 2 * half_w);
    add_rectangle(s, "left-wall", Vec3d(xc, half_w, 0.5 * h), Vec3d::UnitX(), Vec3d::UnitZ(), len,
                  h);
    add_rectangle(s, "right-wall", Vec3d(xc, -half_w, 0.5 * h), Vec3d::UnitX(), Vec3d::UnitZ(), len,
                  h);
    add_rectangle(s, "end-wall", Vec3d(x_end, 0, 0.5 * h), Vec3d::UnitY(), Vec3d::UnitZ(),
                  2 * half_w, h);
    add_rectangle(s, "back-wall", Vec3d(x_back, 0, 0.5 * h), Vec3d::UnitY(), Vec3d::UnitZ(),
                  2 * half_w, h);
    // Thin steel: a 10 mm shelf plate on the left wall and a 10 mm fin standing off the right.
    add_box(s, "shelf-plate", Vec3d(0.8, half_w - 0.25, 0.9), Vec3d(1.6, half_w, 0.91));
    add_box(s, "fin-plate", Vec3d(2.0, -half_w, 0.0), Vec3d(2.01, -half_w + 0.3, 2.0));
    add_cylinder(s, "ceiling-pipe", Vec3d(x_back, 0.5, h - 0.15), Vec3d(x_end, 0.5, h - 0.15),
                 0.05);
    s.scanner.home = pose_from_xyz_rpy(Vec3d(0, 0, 1.2), Vec3d::Zero());
    s.scanner.step_m = Vec3d(0.5, 0, 0);
    return s;
}

SceneDescription stairs_scene() {
    SceneDescription s;
    s.name = "stairs";
    // A flight of six steps with a landing between a side wall (at the tilt axis's pole, 0.9 m
    // to the left) and a wall carrying two pipes on the right; treads and risers are faces
    // 170-280 mm wide meeting at convex and concave edges, seen from 1-4 m.
    const double x0 = 1.0, going = 0.28, rise = 0.17, half_w = 0.8;
    const int steps = 6;
    const double x_top = x0 + steps * going;
    add_rectangle(s, "floor", Vec3d(1.5, -0.15, 0), Vec3d::UnitX(), Vec3d::UnitY(), 5.0, 2.1);
    for (int k = 0; k < steps; ++k) {
        add_box(s, cat({"step-", std::to_string(k)}), Vec3d(x0 + k * going, -half_w, 0),
                Vec3d(x_top, half_w, (k + 1) * rise));
    }
    add_box(s, "landing", Vec3d(x_top, -half_w, 0), Vec3d(x_top + 1.0, half_w, steps * rise));
    add_rectangle(s, "side-wall", Vec3d(1.5, 0.9, 1.25), Vec3d::UnitX(), Vec3d::UnitZ(), 5.0, 2.5);
    add_rectangle(s, "pipe-wall", Vec3d(1.5, -1.2, 1.25), Vec3d::UnitX(), Vec3d::UnitZ(), 5.0, 2.5);
    add_cylinder(s, "pipe-low", Vec3d(-1.0, -1.08, 0.5), Vec3d(4.0, -1.08, 0.5), 0.06);
    add_cylinder(s, "pipe-high", Vec3d(-1.0, -1.12, 1.4), Vec3d(4.0, -1.12, 1.4), 0.04);
    // A 10 mm balustrade plate along the right edge of the flight: thin steel seen edge-on at
    // its top.
    add_box(s, "balustrade-plate", Vec3d(x0, -half_w - 0.01, 0), Vec3d(x_top + 1.0, -half_w, 1.17));
    s.scanner.home = pose_from_xyz_rpy(Vec3d(0, 0, 1.0), Vec3d::Zero());
    s.scanner.step_m = Vec3d(0, -0.4, 0);
    return s;
}

std::vector<std::string> builtin_scene_names() {
    return {"ibeam-channel", "room-corner", "pipes", "corridor", "stairs"};
}

SceneDescription builtin_scene(std::string_view name) {
    if (name == "ibeam-channel") return ibeam_channel_scene();
    if (name == "room-corner") return room_corner_scene();
    if (name == "pipes") return pipes_scene();
    if (name == "corridor") return corridor_scene();
    if (name == "stairs") return stairs_scene();
    std::string names;
    for (const std::string& n : builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
    throw Error(ErrorCode::kInvalidParameter,
                cat({"unknown scene '", name, "' (built in: ", names, ")"}));
}

}  // namespace surfgrow::scanner
