// Stanford PLY point clouds: the vertex element's x, y, z, normals and label; everything else is
// skipped.
#pragma once

#include <ostream>
#include <string_view>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/io/cloud_options.hpp"

namespace surfgrow::io {

/// Reads a PLY file held in memory (ascii, binary_little_endian or binary_big_endian).
///
/// x, y, z may have any scalar type; other properties and other elements (faces with lists,
/// before or after the vertices) are skipped. Float x, y, z are stored as they are; wider types
/// get an offset when large (docs/formats.md). The scalar property options.label_field fills
/// cloud.labels; with options.read_normals, scalar properties nx, ny and nz (all three, any type)
/// fill cloud.normals as float. With options.read_scans, a file whose header has "comment surfgrow
/// scan_origin k x y z" lines (k = 0, 1, ...) must have an integer vertex property "scan" below
/// their count; it fills cloud.scan_index and the origins cloud.scan_origins (and cloud.viewpoint
/// when there is one scan). `source` names the file in messages. Throws Error(kMalformedInput) for
/// a file that breaks the format, is truncated or whose counts do not match its size.
[[nodiscard]] PointCloud read_ply(std::string_view bytes, std::string_view source,
                                  const ReadOptions& options = {});

/// Writes one vertex element: float x y z (double, with the offset added back, when
/// cloud.offset is non-zero), float nx ny nz when `write_normals` and the cloud has normals, and
/// int label when `write_labels` and the cloud has labels; with `write_scans`, uint scan and one
/// "comment surfgrow scan_origin k x y z" line per scan (file coordinates, shortest round-trip
/// form) when the cloud has a scan index. Throws Error(kInvalidParameter), writing nothing, when
/// the cloud's normals are not one per point.
void write_ply(std::ostream& out, const CloudView& cloud,
               PlyEncoding encoding = PlyEncoding::kBinaryLittleEndian, bool write_labels = true,
               bool write_scans = false, bool write_normals = true);

}  // namespace surfgrow::io
