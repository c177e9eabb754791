// The pictures of a result: the overview `grow` writes (and `render` draws by default) and the
// corner close-up `demo` writes (and `render --close-up` draws). One definition for all of them.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene.hpp"

namespace surfgrow::cli {

struct SurfacesPicture {
    render::Scene scene;
    render::RenderOptions options;
};

/// How disks seen from behind are drawn, for normals oriented by `source`: ghosted only when the
/// normals face a sensor that was known (scan origins, a viewpoint). The frame origin is a guess
/// (a world-frame cloud may have it on its floor, where half the floor's normals then point
/// down), and +z leaves walls either way: both sides shown.
[[nodiscard]] render::BackFaces back_faces_for(OrientationSource source);

/// Every surface as a disk, coloured by its bound plane (`plane_of_surface`, one per surface;
/// empty: a colour per surface), with its normal where the disk is big enough on screen; iso
/// view framed on the structure; the summary legend; back faces by back_faces_for.
[[nodiscard]] SurfacesPicture surfaces_picture(const std::vector<Surface>& surfaces,
                                               const GrowStats& stats,
                                               std::span<const std::int32_t> plane_of_surface,
                                               const std::string& units, int threads);

/// Turns the overview into a close-up of the corner where three bound planes meet
/// (render::find_corner), captioned with its width. False (the picture unchanged) when the
/// result has no such corner or is not coloured by plane.
bool make_corner_close_up(SurfacesPicture& picture, std::span<const std::int32_t> plane_of_surface);

/// Stages surfaces.png (`overview`) and corner.png (`close_up`) of a result into `tx`; without a
/// corner, corner.png is dropped. grow writes them; planes draws them again, so that their
/// colours are the new planes'.
void stage_surfaces_pictures(io::OutputTransaction& tx, const std::vector<Surface>& surfaces,
                             const GrowStats& stats, std::span<const std::int32_t> plane_of_surface,
                             const std::string& units, int threads, bool overview, bool close_up);

}  // namespace surfgrow::cli
