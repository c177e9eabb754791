// Colours for groups of surfaces (bound planes): faces that meet get different colours.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/surface.hpp"
#include "surfgrow/render/color.hpp"

namespace surfgrow::render {

/// The colours groups are drawn in: eight hues far enough apart to tell faces apart under any
/// shading, none of them the normals' red or the unassigned grey (the "tab10" palette without its
/// red and grey). Eight are enough: the faces that meet form an (almost) planar map.
inline constexpr std::array<Rgb, 8> kGroupPalette{{{31, 119, 180},
                                                   {255, 127, 14},
                                                   {44, 160, 44},
                                                   {148, 103, 189},
                                                   {140, 86, 75},
                                                   {227, 119, 194},
                                                   {188, 189, 34},
                                                   {23, 190, 207}}};

/// One colour per surface, by its group (`groups[i]`, e.g. its bound plane; -1: kUnassignedGrey).
/// Groups whose surfaces lie within a few median radii of each other (faces that meet at an
/// edge, or lie side by side) get different colours of kGroupPalette wherever eight colours allow
/// it; larger groups choose first, each the colour its neighbours touch least and, among those,
/// the one fewest groups have so far (so nearby faces that do not touch differ as well).
/// Deterministic. Throws Error(kInvalidParameter) unless `groups` has one
/// entry per surface.
[[nodiscard]] std::vector<Rgb> group_colors(const std::vector<Surface>& surfaces,
                                            std::span<const std::int32_t> groups);

}  // namespace surfgrow::render
