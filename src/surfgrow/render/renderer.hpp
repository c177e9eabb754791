// Rendering a Scene to an Image: framing, shading, the z-buffered rasterizer, legend and axes.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "surfgrow/render/camera.hpp"
#include "surfgrow/render/close_up.hpp"
#include "surfgrow/render/framing.hpp"
#include "surfgrow/render/image.hpp"
#include "surfgrow/render/scene.hpp"

namespace surfgrow::render {

/// How disks are lit: Lambert shading from one directional light, two-sided (a disk seen from
/// behind is lit as if seen from the front), so planes of different orientation get different
/// shades and the structure reads in 3D.
struct Lighting {
    /// Towards the light, in camera coordinates (right, up, towards the viewer): from the upper
    /// left, in front. In the iso view this gives top, front and right faces three shades.
    Vec3d direction = Vec3d(-0.45, 0.65, 0.6);
    double ambient = 0.36;  ///< brightness of a disk facing away from the light
    double diffuse = 0.64;  ///< added for a disk facing the light
    /// Aerial perspective: the farthest disks are mixed this much with the background.
    double fog = 0.22;
};

/// What becomes of disks whose normal faces away from the viewer, with their points and normals
/// (ScenePoint::disk, Segment::disk). The grower orients normals towards the sensor, so these
/// are the surfaces seen from behind: in an enclosed scan (a room, the I-beam channel under its
/// deck) the near walls, which hide the inside from any view outside.
enum class BackFaces {
    kShow,   ///< draw them like the others
    kGhost,  ///< see-through (a third of their samples, lighter, no outlines, no points or
             ///< normals): the inside shows through them
    kCull,   ///< leave them out, with their points and normals
};

/// Everything about the picture that is not the scene.
struct RenderOptions {
    int width = 1600;   ///< pixels, 16..16384
    int height = 1200;  ///< pixels, 16..16384
    View view = View::kIso;
    /// Overrides `view` and the automatic framing when set (its frame is in output pixels).
    std::optional<Camera> camera;
    /// What the automatic framing fits: the structure (stray patches may fall outside) or all.
    Framing framing = Framing::kBulk;
    /// A close-up instead of the whole scene (overrides `view` and `framing`; not `camera`).
    std::optional<CloseUp> close_up;
    /// Free space around the fitted scene, as a fraction of the picture's smaller side (0..0.4).
    double margin = 0.04;
    /// Samples per pixel along each axis (1..4) for antialiasing.
    int supersample = 3;
    /// Threads rasterizing tiles; 0 = all cores. The picture does not depend on it.
    int threads = 0;
    Rgb background{255, 255, 255};
    Rgb text_color{40, 40, 40};
    Lighting lighting;
    /// Disks seen from behind. kGhost suits clouds whose normals face the sensor (a viewpoint
    /// or scan origins were known); with normals merely facing up (georeferenced clouds, no
    /// viewpoint) vertical surfaces face either way, so use kShow.
    BackFaces back_faces = BackFaces::kGhost;
    /// Outer ring of each disk drawn darker, so single disks stay visible where same-coloured
    /// disks overlap (colouring by bound plane). Fraction of the shaded colour kept in the ring.
    double rim_shade = 0.8;
    /// Dark lines where the depth jumps (silhouettes, an edge passing in front of a face).
    bool outlines = true;
    double point_size = 1.6;  ///< diameter of raw points, pixels
    double line_width = 1.4;  ///< width of normals, pixels
    /// A normal that belongs to a disk (Segment::disk) is drawn only when its disk's radius is at
    /// least this many pixels: close enough for the normal to mean something, not a red haze.
    /// 0 draws them all.
    double normal_min_radius = 16.0;
    /// Disks seen (nearly) edge-on are drawn at least this thick (pixels), so planes parallel
    /// to the view direction still show as lines.
    double min_disk_thickness = 0.8;
    bool legend = true;  ///< the scene's legend line under the picture
    bool axes = true;    ///< a small x/y/z axis triad in the lower right corner
    /// A scale bar; in iso views and close-ups labelled "across the view" (true for lengths
    /// square to the view direction, shorter for others).
    bool scale_bar = true;
    std::string units;  ///< unit name for the scale bar ("m", "mm"); empty writes none
    /// Font for the text; empty: Font::find_default(), and with no font on the machine the
    /// picture has no text. A font_file that does not load is an Error(kCannotOpen).
    std::filesystem::path font_file;
};

/// Throws Error(kInvalidParameter) naming the first option out of range.
void validate(const RenderOptions& options);

/// The camera render_scene() uses: options.camera; or the close-up's; or the view preset scaled
/// and centred so that the disks and normals (the points only if there are neither) fit the area
/// above the legend band, only the bulk of the disks (bulk_disks) unless options.framing is
/// kAll. Validates the options.
[[nodiscard]] Camera frame_scene(const Scene& scene, const RenderOptions& options);

/// The shaded colour of a disk of colour `color` and unit `normal` under `lighting` (before fog).
[[nodiscard]] Rgb shade(Rgb color, const Vec3d& normal, const Camera& camera,
                        const Lighting& lighting);

/// Renders `scene`. Deterministic: the same scene and options give the same pixels, whatever
/// the thread count. Throws Error(kInvalidParameter) for invalid options, Error(kCannotOpen)
/// for a font_file that does not load.
[[nodiscard]] Image render_scene(const Scene& scene, const RenderOptions& options = {});

}  // namespace surfgrow::render
