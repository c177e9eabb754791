// PCL's Point Cloud Data files (v0.7, and v0.6 where it differs harmlessly).
#pragma once

#include <ostream>
#include <string_view>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/io/cloud_options.hpp"

namespace surfgrow::io {

/// Reads a PCD file held in memory: DATA ascii, binary or binary_compressed (LZF); fields of
/// any PCD type and COUNT, `_` padding fields; x, y, z kept, options.label_field read into
/// cloud.labels and (options.read_normals) normal_x normal_y normal_z into cloud.normals; every
/// point kept in order, NaN ones and those of organized clouds included.
/// A VIEWPOINT other than the default "0 0 0 1 0 0 0" sets cloud.viewpoint (its translation).
/// `source` names the file in messages. Throws Error(kMalformedInput) for a file that breaks the
/// format, is truncated or whose counts do not match its size.
[[nodiscard]] PointCloud read_pcd(std::string_view bytes, std::string_view source,
                                  const ReadOptions& options = {});

/// Writes a v0.7 PCD: fields x y z (F4, or F8 with the offset added back when cloud.offset is
/// non-zero), normal_x normal_y normal_z (F4, PCL's PointNormal names) when `write_normals` and
/// the cloud has normals, and label (I4) when `write_labels` and the cloud has labels;
/// WIDTH = POINTS, HEIGHT 1; VIEWPOINT from cloud.viewpoint (identity rotation). Throws
/// Error(kCannotWrite) when a binary_compressed body would exceed the format's 4 GiB limit, and
/// Error(kInvalidParameter), writing nothing, when the cloud's normals are not one per point.
void write_pcd(std::ostream& out, const CloudView& cloud,
               PcdEncoding encoding = PcdEncoding::kBinary, bool write_labels = true,
               bool write_normals = true);

}  // namespace surfgrow::io
