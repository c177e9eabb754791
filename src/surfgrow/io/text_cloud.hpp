// Plain-text point clouds, one point per line (.xyz, .txt, .csv, .pts).
#pragma once

#include <ostream>
#include <string_view>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/io/cloud_options.hpp"

namespace surfgrow::io {

/// Reads a text cloud held in memory.
///
/// Values are separated by blanks, or by ';' or ',' on lines that contain one (then an empty
/// field is a value too). '#' starts a comment; blank lines are skipped. A first line holding one
/// integer (the point count of .pts files) is skipped. A header row (a row with fewer than three
/// numbers, before any point) naming x, y and z in any order and case ("//X" as CloudCompare
/// writes it, quotes allowed) selects those columns, options.label_field and (with
/// options.read_normals, when it names all three) the normals nx ny nz; otherwise x, y, z
/// are the first three numeric columns of the first point's row. Coordinates are read as double
/// and get an offset when large. A malformed row throws Error(kMalformedInput) naming `source`
/// and the line number; so does a file without points.
[[nodiscard]] PointCloud read_text_cloud(std::string_view bytes, std::string_view source,
                                         const ReadOptions& options = {});

/// Writes "x y z" per line, values separated by `delimiter`, in the shortest decimal form that
/// reads back as the same float (double with the offset added back when cloud.offset is
/// non-zero). With `write_normals` and normals in the cloud, "nx ny nz" follow (floats, same
/// form); with `write_labels` and labels in the cloud, the label comes last; either adds a header
/// row naming the columns ("x y z nx ny nz label", "x y z label", ...). With `count_line` the
/// first line is the number of points (.pts). Throws Error(kInvalidParameter), writing nothing,
/// when the cloud's normals are not one per point.
void write_text_cloud(std::ostream& out, const CloudView& cloud, char delimiter = ' ',
                      bool write_labels = false, bool count_line = false,
                      bool write_normals = true);

}  // namespace surfgrow::io
