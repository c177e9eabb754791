// Scenes that ship with surfgrow: the paper's I-beam channel (Fig. 1), a room corner, pipes, and
// scenes that attack the method: a corridor (walls at the tilt axis's poles, far end) and stairs.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::scanner {

/// Dimensions of the I-beam channel, metres. World frame: x along the girders, y across the
/// channel (girder centres at +-girder_spacing/2), z up from the robot's scaffold floor.
struct IBeamChannelParams {
    double length_m = 4.0;          ///< girder length (x from -length/2 to +length/2)
    double girder_spacing_m = 1.6;  ///< centre-to-centre distance of the two girders
    double depth_m = 1.0;           ///< overall girder depth (welded plate girder)
    double flange_width_m = 0.40;
    double flange_thickness_m = 0.030;
    double web_thickness_m = 0.014;
    double girder_bottom_z_m = 1.2;  ///< underside of the bottom flanges above the floor
    double deck_thickness_m = 0.20;  ///< concrete deck slab on the girders
    double stiffener_thickness_m = 0.012;
    double stiffener_width_m = 0.15;  ///< outstand from the web into the channel
    std::vector<double> stiffener_x_m = {-1.5, -0.75, 0.75, 1.5};
    double splice_length_m = 0.40;  ///< web splice plate, along x (centred at x = 0)
    double splice_height_m = 0.60;
    double splice_thickness_m = 0.016;
    double bolt_radius_m = 0.017;    ///< M20 heavy hex head (34 mm across flats) as a cylinder
    double bolt_head_m = 0.013;      ///< head height
    double scanner_height_m = 1.45;  ///< scanner origin above the floor, channel centre
};

/// The underside of a steel bridge, as in Fig. 1 of the paper: two welded plate girders (each a
/// bottom flange, a web and a top flange), the deck slab on them, stiffener plates on the inner
/// face of each web, a bolted web splice on each girder (12 bolts each) and the scaffold floor.
/// The scanner looks up into the channel (pitch -90 deg: its forward axis is world +z, its tilt
/// axis world y, so the pan fan cuts across the channel and the tilt sweeps along it).
[[nodiscard]] SceneDescription ibeam_channel_scene(const IBeamChannelParams& params = {});

/// A floor and two walls meeting at a corner 1 m in front of the scanner on each side; the
/// scanner 0.6 m above the floor looking into the corner (yaw 45 deg).
[[nodiscard]] SceneDescription room_corner_scene();

/// A harder scene: three horizontal pipes of different radii on brackets in front of a wall, a
/// vertical pipe in front of them (occlusion), a pipe flange and a valve body; curved surfaces,
/// thin parts and many depth edges. Scanner 0.9 m above the floor, looking at the wall.
[[nodiscard]] SceneDescription pipes_scene();

/// A corridor 2 m wide and 2.5 m high, seen along its length: both side walls at the tilt axis's
/// poles (1 m), an end wall at 3.5 m, a 10 mm shelf plate and fin, a ceiling pipe.
[[nodiscard]] SceneDescription corridor_scene();

/// A flight of six steps and a landing between a side wall (at the tilt axis's pole) and a wall
/// with two pipes, a 10 mm balustrade plate along the flight; scanner 1 m above the floor.
[[nodiscard]] SceneDescription stairs_scene();

/// "ibeam-channel", "room-corner", "pipes", "corridor", "stairs".
[[nodiscard]] std::vector<std::string> builtin_scene_names();

/// The built-in scene called `name`; throws Error(kInvalidParameter) listing the names otherwise.
[[nodiscard]] SceneDescription builtin_scene(std::string_view name);

}  // namespace surfgrow::scanner
