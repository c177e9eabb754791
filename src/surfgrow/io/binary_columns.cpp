#include "surfgrow/io/binary_columns.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "surfgrow/io/ascii_scan.hpp"
#include "surfgrow/io/io_error.hpp"
#include "surfgrow/io/point_builder.hpp"

namespace surfgrow::io {

namespace {

static_assert(sizeof(Vec3f) == 3 * sizeof(float), "Vec3f must be three packed floats");

// points[i][axis] = value i of the column, minus `offset`.
template <typename T, bool kSwap>
void axis_kernel(const char* p, std::size_t stride, std::size_t n, Vec3f* points, int axis,
                 double offset) {
    if constexpr (std::is_same_v<T, float>) {
        if (offset == 0.0) {
            for (std::size_t i = 0; i < n; ++i) {
                points[i].data()[axis] = load_value<float, kSwap>(p + i * stride);
            }
            return;
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        const double v = static_cast<double>(load_value<T, kSwap>(p + i * stride));
        points[i].data()[axis] = static_cast<float>(v - offset);
    }
}

template <typename T, bool kSwap>
void label_kernel(const char* p, std::size_t stride, std::size_t n, int32_t* labels,
                  std::string_view source) {
    for (std::size_t i = 0; i < n; ++i) {
        const T v = load_value<T, kSwap>(p + i * stride);
        if constexpr (std::is_floating_point_v<T>) {
            if (!label_from_double(static_cast<double>(v), labels[i])) {
                throw_malformed(
                    source, cat({"point ", count_str(i), " has label ", num(static_cast<double>(v)),
                                 ", which is not a 32-bit integer"}));
            }
        } else if constexpr (sizeof(T) == 8) {
            if (!label_from_double(static_cast<double>(v), labels[i])) {
                throw_malformed(source, cat({"point ", count_str(i), " has label ",
                                             std::to_string(v), ", beyond 32 bits"}));
            }
        } else {
            // 8/16-bit values widen; uint32 values above INT32_MAX wrap (0xFFFFFFFF reads as -1).
            labels[i] = static_cast<int32_t>(static_cast<uint32_t>(v));
        }
    }
}

// normals[i][axis] = value i of the column, as float (any type: normals need no offset).
template <typename T, bool kSwap>
void normal_kernel(const char* p, std::size_t stride, std::size_t n, Vec3f* normals, int axis) {
    for (std::size_t i = 0; i < n; ++i) {
        normals[i].data()[axis] = static_cast<float>(load_value<T, kSwap>(p + i * stride));
    }
}

void read_normal_axis(const char* data, const Column& c, std::size_t n, bool swap, Vec3f* normals,
                      int axis) {
    visit_scalar(c.type, [&](auto tag) {
        using T = decltype(tag);
        const char* p = data + c.base;
        if (swap) {
            normal_kernel<T, true>(p, c.stride, n, normals, axis);
        } else {
            normal_kernel<T, false>(p, c.stride, n, normals, axis);
        }
    });
}

void read_axis(const char* data, const Column& c, std::size_t n, bool swap, Vec3f* points, int axis,
               double offset) {
    visit_scalar(c.type, [&](auto tag) {
        using T = decltype(tag);
        const char* p = data + c.base;
        if (swap) {
            axis_kernel<T, true>(p, c.stride, n, points, axis, offset);
        } else {
            axis_kernel<T, false>(p, c.stride, n, points, axis, offset);
        }
    });
}

bool is_packed_float_xyz(const std::array<Column, 3>& xyz, bool swap) {
    for (int a = 0; a < 3; ++a) {
        if (xyz[a].type != ScalarType::kFloat32 || xyz[a].stride != xyz[0].stride ||
            xyz[a].base != xyz[0].base + 4 * static_cast<std::size_t>(a)) {
            return false;
        }
    }
    return !swap;
}

// The first point, in file order, that the offset rule applies to (see offset_for).
std::optional<Vec3d> find_offset(const char* data, std::size_t n, const std::array<Column, 3>& xyz,
                                 bool swap, const Vec3f* points) {
    // The floats already read find candidates quickly; a float is within 1e-3 of its value here,
    // so a slightly lower bar misses none. The exact test runs on the file's own values.
    constexpr float kBar = static_cast<float>(kOffsetThreshold) - 1.0f;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3f& p = points[i];
        if (!(std::abs(p.x()) > kBar || std::abs(p.y()) > kBar || std::abs(p.z()) > kBar)) {
            continue;
        }
        double v[3];
        for (int a = 0; a < 3; ++a) {
            v[a] = load_as_double(data + xyz[a].base + i * xyz[a].stride, xyz[a].type, swap);
        }
        if (auto off = offset_for(v[0], v[1], v[2])) return off;
    }
    return std::nullopt;
}

}  // namespace

void read_columns(const char* data, std::size_t n, const std::array<Column, 3>& xyz,
                  const Column* label, const std::array<Column, 3>* normals, bool swap,
                  std::string_view source, PointCloud& cloud) {
    cloud.points.resize(n);
    if (label) cloud.labels.resize(n);
    if (normals) cloud.normals.resize(n);
    if (n == 0) return;  // data() may be null, and memcpy must not see that
    Vec3f* points = cloud.points.data();
    if (is_packed_float_xyz(xyz, swap)) {
        // The common case (float x y z first in each record): plain copies.
        const char* p = data + xyz[0].base;
        if (xyz[0].stride == sizeof(Vec3f)) {
            std::memcpy(static_cast<void*>(points), p, n * sizeof(Vec3f));
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                std::memcpy(static_cast<void*>(points + i), p + i * xyz[0].stride, sizeof(Vec3f));
            }
        }
    } else {
        for (int a = 0; a < 3; ++a) read_axis(data, xyz[a], n, swap, points, a, 0.0);
        const bool wide = is_wide(xyz[0].type) || is_wide(xyz[1].type) || is_wide(xyz[2].type);
        if (wide) {
            if (const auto off = find_offset(data, n, xyz, swap, points)) {
                cloud.offset = *off;
                for (int a = 0; a < 3; ++a) read_axis(data, xyz[a], n, swap, points, a, (*off)[a]);
            }
        }
    }
    if (normals) {
        for (int a = 0; a < 3; ++a) {
            read_normal_axis(data, (*normals)[a], n, swap, cloud.normals.data(), a);
        }
    }
    if (label) {
        visit_scalar(label->type, [&](auto tag) {
            using T = decltype(tag);
            const char* p = data + label->base;
            if (swap) {
                label_kernel<T, true>(p, label->stride, n, cloud.labels.data(), source);
            } else {
                label_kernel<T, false>(p, label->stride, n, cloud.labels.data(), source);
            }
        });
    }
}

void check_padding_tail(std::string_view bytes, std::size_t pos, std::string_view source) {
    for (std::size_t i = pos; i < bytes.size(); ++i) {
        if (bytes[i] != '\0' && !is_blank(bytes[i])) {
            throw_malformed(source, cat({count_str(bytes.size() - pos),
                                         " bytes follow the data the header declares"}));
        }
    }
}

}  // namespace surfgrow::io
