// What the interactive viewer shows: the layers of one page, independent of where they came from.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/render/color.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene.hpp"

namespace surfgrow::view {

/// One bound plane as a filled, see-through polygon with its outline (planes.json).
struct PlanePolygon {
    std::int32_t plane = -1;                ///< the bound plane's id
    std::vector<Vec3d> outline;             ///< outer boundary, vertices in order (>= 3)
    std::vector<std::vector<Vec3d>> holes;  ///< inner boundaries, each >= 3 vertices
    render::Rgb color;                      ///< as the disks of this plane when coloured by plane
};

/// Everything one page shows. Positions are in the result's frame: file coordinates minus
/// `offset`, as in io::StoredResult. Layers that are empty are left out of the page; the two
/// optional layers are listed (greyed) when absent, so the page says what it could show.
struct ViewerScene {
    std::string title;               ///< page title and panel heading (the result folder)
    std::string units;               ///< the result's length unit ("m", "mm")
    std::string legend;              ///< "276480 points -> 5231 surfaces, 99.4% registered"
    std::vector<std::string> notes;  ///< more lines for the panel (e.g. the cloud was subsampled)
    Vec3d offset = Vec3d::Zero();    ///< file coordinates = position + offset
    /// How disks seen from behind start out (the page can switch): kGhost when normals face the
    /// sensor, so the inside of an enclosed scan shows through its near walls, as in the PNG.
    render::BackFaces back_faces = render::BackFaces::kGhost;

    std::vector<render::ScenePoint> points;  ///< the cloud layer (colour per point)
    /// The surfaces layer: disks (radius <= 0 or non-finite ones are left out); the normals
    /// layer draws each disk's normal, one radius long, from its centre.
    std::vector<render::Disk> disks;
    /// Empty, or one per disk: its colour by bound plane (the page then offers the choice).
    std::vector<render::Rgb> disk_plane_colors;
    /// The bound-planes layer; nullopt when the result has no planes.json.
    std::optional<std::vector<PlanePolygon>> planes;
    /// The coverage-path layer: goals in order; nullopt when the result has no coverage.json.
    std::optional<std::vector<Vec3d>> path;
};

}  // namespace surfgrow::view
