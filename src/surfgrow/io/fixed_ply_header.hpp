// The header of a PLY file surfgrow writes in one fixed binary layout (surfaces.ply, planes.ply,
// coverage.ply, collision_spheres.ply), written and read back by their own strict readers; clouds
// of any layout go through ply_reader instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace surfgrow::io {

struct FixedPlyHeader {
    bool binary_little_endian = false;
    /// "element NAME" and each property's "TYPE NAME" (or "list ..."), in file order: the
    /// caller compares it with the layout it writes.
    std::vector<std::string> layout;
    /// Each element's name and count, in file order (a count that does not parse is 0).
    std::vector<std::pair<std::string, std::uint64_t>> elements;
    std::string result_id;  ///< from a "comment result_id ID" line; empty without one
    std::size_t body = 0;   ///< offset of the first byte after "end_header\n"

    /// Whether the first element's first property is "double x": surfgrow writes positions in
    /// double for a georeferenced cloud, in float otherwise.
    [[nodiscard]] bool positions_in_double() const {
        return layout.size() > 1 && layout[1] == "double x";
    }
    /// Whether the file is binary little-endian with one element, "vertex", of exactly
    /// `properties` ("TYPE NAME" each, in file order).
    [[nodiscard]] bool is_vertex_layout(std::span<const std::string> properties) const;
};

/// The header of a binary little-endian PLY of `count` vertices of `properties` ("TYPE NAME"
/// each): `what` as its first comment, then the units and the result_id.
[[nodiscard]] std::string fixed_ply_head(std::string_view what, std::string_view units,
                                         std::string_view result_id, std::size_t count,
                                         std::span<const std::string> properties);

/// Bytes of one vertex of `properties`: double 8, uchar 1, any other (float, int, uint) 4.
[[nodiscard]] std::size_t record_bytes(std::span<const std::string> properties);

/// Reads the header of `bytes`. Throws Error(kMalformedInput) naming `source` when there is no
/// "ply" line or no end_header.
[[nodiscard]] FixedPlyHeader read_fixed_ply_header(std::string_view bytes, std::string_view source);

}  // namespace surfgrow::io
