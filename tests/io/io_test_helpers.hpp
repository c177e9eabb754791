// Helpers shared by the surfgrow_io tests: sample clouds, comparisons, hand-written files.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow::test {

/// n points in a 10 m box around the origin (seeded); every 7th point NaN when `with_nan`,
/// labels 0..9 when `with_labels`.
PointCloud sample_cloud(std::size_t n, uint64_t seed, bool with_nan, bool with_labels);

/// The same points, georeferenced: offset (512345, 5412345, 312) and points within +-50 m.
PointCloud georeferenced_cloud(std::size_t n, uint64_t seed);

/// Gives `cloud` one normal per point: seeded unit vectors, and at fixed places values that try
/// the ASCII round trip: NaN, -0, subnormals, FLT_MAX, +-7.038531e-26 (whose shortest text,
/// read as a double and then rounded to float, gives the next float instead).
void add_normals(PointCloud& cloud, uint64_t seed);

/// Expects the same normals, bit for bit (NaN where NaN: text writes every NaN as "nan").
void expect_same_normals(const PointCloud& expected, const PointCloud& actual);

/// Point i in file coordinates (offset added back).
inline Vec3d absolute(const PointCloud& cloud, std::size_t i) {
    return cloud.points[i].cast<double>() + cloud.offset;
}

/// Expects the same number of points, each at the same absolute position (offset added) within
/// `tolerance`, NaN where the other is NaN, and the same labels.
void expect_same_cloud(const PointCloud& expected, const PointCloud& actual, double tolerance);

/// What a writer puts on a stream, as bytes.
std::string written(const std::function<void(std::ostream&)>& writer);

/// Runs `f`, expects it to throw surfgrow::Error with `code` and a message containing `needle`
/// (e.g. the file name); returns the message.
std::string expect_error(const std::function<void()>& f, ErrorCode code, std::string_view needle);

/// Appends a value's bytes in big-endian order (test-side writer for binary_big_endian PLY).
template <typename T>
void append_big_endian(std::string& out, T v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (std::size_t i = sizeof(T); i-- > 0;) out.push_back(bytes[i]);
}

/// Appends a value's bytes in little-endian (host) order.
template <typename T>
void append_little_endian(std::string& out, T v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    out.append(bytes, sizeof(T));
}

}  // namespace surfgrow::test
