// Extracting x, y, z, normals and labels from fixed-size binary records (PLY and PCD bodies).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/io/scalar_type.hpp"

namespace surfgrow::io {

/// Where one value of every record lives: value i is at data + base + i * stride.
struct Column {
    std::size_t base = 0;
    std::size_t stride = 0;
    ScalarType type = ScalarType::kFloat32;
};

/// Fills cloud.points with n points from the x, y, z columns (cloud.labels from `label` and
/// cloud.normals from the three `normals` columns, converted to float, when given), applying the
/// offset rule when a coordinate type is wider than float. `swap` reverses each value's bytes
/// (big-endian data). The caller has checked that every column lies inside `data`. Throws
/// Error(kMalformedInput) naming `source` for a label that is not an integer.
void read_columns(const char* data, std::size_t n, const std::array<Column, 3>& xyz,
                  const Column* label, const std::array<Column, 3>* normals, bool swap,
                  std::string_view source, PointCloud& cloud);

/// Bytes after the last record are tolerated only as padding (zeros or blanks: PCL pads binary
/// PCD files with zeros), so a header that undercounts its data does not go unnoticed. Throws
/// Error(kMalformedInput) naming `source` otherwise.
void check_padding_tail(std::string_view bytes, std::size_t pos, std::string_view source);

}  // namespace surfgrow::io
