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

std::vector<std::string> builtin_scene_names() {
    return {"ibeam-channel", "room-corner", "pipes"};
}

SceneDescription builtin_scene(std::string_view name) {
    if (name == "ibeam-channel") return ibeam_channel_scene();
    if (name == "room-corner") return room_corner_scene();
    if (name == "pipes") return pipes_scene();
    throw Error(ErrorCode::kInvalidParameter,
                cat({"unknown scene '", name, "' (built in: ibeam-channel, room-corner, pipes)"}));
}

}  // namespace surfgrow::scanner
