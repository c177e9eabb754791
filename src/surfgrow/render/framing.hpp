// What a picture is framed on: the structure that was scanned, not the stray patches around it.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "surfgrow/render/scene.hpp"

namespace surfgrow::render {

/// How the automatic camera frames a scene.
enum class Framing {
    kBulk,  ///< the structure: see bulk_disks(); stray patches far from it may fall outside
    kAll,   ///< every disk
};

/// "bulk" or "all"; anything else throws Error(kInvalidParameter).
[[nodiscard]] Framing parse_framing(std::string_view name);
[[nodiscard]] std::string_view framing_name(Framing framing);

/// Disks whose centres lie within this many median disk radii of each other (up to twice that:
/// they are linked through cubes of this side) belong to one piece of structure.
inline constexpr double kLinkRadii = 6.0;

/// One flag per disk, 1 for the disks a picture is framed on. Disks are linked into pieces
/// (kLinkRadii); the pieces are taken from the largest down until they hold 80 % of the usable
/// disks, and every piece with at least 5 % of them is taken too; then every piece whose box
/// comes within a tenth of the taken box's largest side of it. So a scan's structure is framed
/// whole, thinned-out far ends included, while a few sparse floor patches a metre below it, or
/// returns from far walls, are not; a scene that is all small pieces is framed (almost) whole.
/// Unusable disks (radius <= 0, non-finite) get 0.
[[nodiscard]] std::vector<std::uint8_t> bulk_disks(std::span<const Disk> disks);

/// The median radius of the usable disks; 0 when there are none.
[[nodiscard]] double median_disk_radius(std::span<const Disk> disks);

/// A disk the renderer can draw: finite centre and normal, non-zero normal, finite radius > 0.
[[nodiscard]] bool usable(const Disk& disk);

}  // namespace surfgrow::render
