#include "surfaces_picture.hpp"

#include <cstdio>

#include "surfgrow/core/text.hpp"
#include "surfgrow/render/close_up.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/scene_builder.hpp"

namespace surfgrow::cli {

render::BackFaces back_faces_for(OrientationSource source) {
    const bool sensor_known =
        source == OrientationSource::kScanOrigins || source == OrientationSource::kViewpoint;
    return sensor_known ? render::BackFaces::kGhost : render::BackFaces::kShow;
}

SurfacesPicture surfaces_picture(const std::vector<Surface>& surfaces, const GrowStats& stats,
                                 std::span<const std::int32_t> plane_of_surface,
                                 const std::string& units, int threads) {
    render::SurfaceStyle style;
    style.groups.assign(plane_of_surface.begin(), plane_of_surface.end());
    // Drawn only where a disk is big enough on screen (RenderOptions::normal_min_radius).
    style.normals = true;
    SurfacesPicture p{render::scene_from_surfaces(surfaces, style), {}};
    p.scene.legend =
        render::legend_line(stats.points_in, stats.surfaces, stats.registered_fraction());
    if (!plane_of_surface.empty()) p.scene.legend += ", coloured by bound plane";
    p.options.units = units;
    p.options.threads = threads;
    p.options.back_faces = back_faces_for(stats.orientation);
    return p;
}

bool make_corner_close_up(SurfacesPicture& picture,
                          std::span<const std::int32_t> plane_of_surface) {
    if (plane_of_surface.size() != picture.scene.disks.size()) return false;
    const auto corner = render::find_corner(picture.scene.disks, plane_of_surface);
    if (!corner) return false;
    picture.options.close_up = *corner;
    char across[64];
    std::snprintf(across, sizeof across, "%.3g", 2 * corner->half_size);
    picture.scene.legend = cat(
        {"close-up of a corner, ", across, " ", picture.options.units, " across; normals in red"});
    return true;
}

void stage_surfaces_pictures(io::OutputTransaction& tx, const std::vector<Surface>& surfaces,
                             const GrowStats& stats, std::span<const std::int32_t> plane_of_surface,
                             const std::string& units, int threads, bool overview, bool close_up) {
    if (!overview && !close_up) return;
    SurfacesPicture picture = surfaces_picture(surfaces, stats, plane_of_surface, units, threads);
    if (overview) {
        const render::Image image = render::render_scene(picture.scene, picture.options);
        tx.add("surfaces.png", [&](std::ostream& o) { render::write_png(image, o, threads); });
    }
    if (close_up) {
        if (make_corner_close_up(picture, plane_of_surface)) {
            const render::Image image = render::render_scene(picture.scene, picture.options);
            tx.add("corner.png", [&](std::ostream& o) { render::write_png(image, o, threads); });
        } else {
            tx.drop("corner.png");
        }
    }
}

}  // namespace surfgrow::cli
