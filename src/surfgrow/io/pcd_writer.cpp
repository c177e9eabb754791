// Writing PCD v0.7: x y z [normal_x normal_y normal_z] [label], ascii, binary or
// binary_compressed (LZF).
#include <liblzf/lzf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "surfgrow/io/cloud_layout.hpp"
#include "surfgrow/io/output_buffer.hpp"
#include "surfgrow/io/pcd.hpp"

namespace surfgrow::io {

namespace {

void write_header(OutputBuffer& buf, const CloudView& cloud, const CloudLayout& layout,
                  PcdEncoding encoding) {
    const std::string n = std::to_string(cloud.size());
    const std::string_view c = layout.doubles ? "8" : "4";
    // Normals after x y z, the label last (as write_ascii, write_binary, write_compressed).
    const bool nrm = layout.normals;
    const bool lab = layout.labels;
    buf.append("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n");
    buf.append(
        cat({"FIELDS x y z", nrm ? " normal_x normal_y normal_z" : "", lab ? " label" : "", "\n"}));
    buf.append(cat({"SIZE ", c, " ", c, " ", c, nrm ? " 4 4 4" : "", lab ? " 4" : "", "\n"}));
    buf.append(cat({"TYPE F F F", nrm ? " F F F" : "", lab ? " I" : "", "\n"}));
    buf.append(cat({"COUNT 1 1 1", nrm ? " 1 1 1" : "", lab ? " 1" : "", "\n"}));
    buf.append(cat({"WIDTH ", n, "\nHEIGHT 1\nVIEWPOINT "}));
    if (cloud.viewpoint) {
        const Vec3d v = *cloud.viewpoint + cloud.offset;
        for (int a = 0; a < 3; ++a) {
            buf.put_number(v[a]);
            buf.put(' ');
        }
        buf.append("1 0 0 0\n");
    } else {
        buf.append("0 0 0 1 0 0 0\n");
    }
    buf.append(cat({"POINTS ", n, "\nDATA ", to_string(encoding), "\n"}));
}

void write_ascii(OutputBuffer& buf, const CloudView& cloud, const CloudLayout& layout) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            if (a > 0) buf.put(' ');
            if (layout.doubles) {
                buf.put_number(absolute_point(cloud, i)[a]);
            } else {
                buf.put_number(cloud.points[i][a]);
            }
        }
        if (layout.normals) {
            for (int a = 0; a < 3; ++a) {
                buf.put(' ');
                buf.put_number(cloud.normals[i][a]);
            }
        }
        if (layout.labels) {
            buf.put(' ');
            buf.put_number(cloud.labels[i]);
        }
        buf.put('\n');
    }
}

// PCD binary data is little-endian (PCL writes the host's order, little-endian in practice).
constexpr bool kSwap = !kHostIsLittleEndian;

void write_binary(OutputBuffer& buf, const CloudView& cloud, const CloudLayout& layout) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (layout.doubles) {
            const Vec3d p = absolute_point(cloud, i);
            for (int a = 0; a < 3; ++a) buf.put_binary(p[a], kSwap);
        } else {
            for (int a = 0; a < 3; ++a) buf.put_binary(cloud.points[i][a], kSwap);
        }
        if (layout.normals) {
            for (int a = 0; a < 3; ++a) buf.put_binary(cloud.normals[i][a], kSwap);
        }
        if (layout.labels) buf.put_binary(cloud.labels[i], kSwap);
    }
}

template <typename T>
char* put_raw(char* out, T v) {
    if constexpr (kSwap) v = byteswap_value(v);
    std::memcpy(out, &v, sizeof v);
    return out + sizeof v;
}

void write_compressed(OutputBuffer& buf, const CloudView& cloud, const CloudLayout& layout) {
    // Each field's values one after another (x x x ... y y y ...) compress far better.
    const std::size_t n = cloud.size();
    const std::size_t value = layout.doubles ? 8 : 4;
    const std::size_t size = n * (3 * value + (layout.normals ? 12 : 0) + (layout.labels ? 4 : 0));
    if (size > std::numeric_limits<uint32_t>::max()) {
        throw Error(ErrorCode::kCannotWrite,
                    cat({"binary_compressed PCD holds at most 4 GiB of data; this cloud needs ",
                         std::to_string(size), " bytes (use binary)"}));
    }
    const auto raw = std::make_unique_for_overwrite<char[]>(size == 0 ? 1 : size);
    char* p = raw.get();
    for (int a = 0; a < 3; ++a) {
        for (std::size_t i = 0; i < n; ++i) {
            if (layout.doubles) {
                p = put_raw(p, absolute_point(cloud, i)[a]);
            } else {
                p = put_raw(p, cloud.points[i][a]);
            }
        }
    }
    if (layout.normals) {
        for (int a = 0; a < 3; ++a) {
            for (std::size_t i = 0; i < n; ++i) p = put_raw(p, cloud.normals[i][a]);
        }
    }
    if (layout.labels) {
        for (std::size_t i = 0; i < n; ++i) p = put_raw(p, cloud.labels[i]);
    }
    // LZF output is at most about 104% of its input.
    const std::size_t capacity = size + size / 16 + 64;
    const auto packed = std::make_unique_for_overwrite<char[]>(capacity);
    unsigned used = 0;
    if (size > 0) {
        used = lzf_compress(raw.get(), static_cast<unsigned>(size), packed.get(),
                            static_cast<unsigned>(std::min<std::size_t>(capacity, UINT32_MAX)));
        if (used == 0) throw Error(ErrorCode::kInternal, "LZF compression failed");
    }
    buf.put_binary(static_cast<uint32_t>(used), kSwap);
    buf.put_binary(static_cast<uint32_t>(size), kSwap);
    buf.append(std::string_view(packed.get(), used));
}

}  // namespace

void write_pcd(std::ostream& out, const CloudView& cloud, PcdEncoding encoding, bool write_labels,
               bool write_normals) {
    const CloudLayout layout = layout_for(cloud, write_labels, write_normals);
    OutputBuffer buf(out);
    write_header(buf, cloud, layout, encoding);
    switch (encoding) {
        case PcdEncoding::kAscii:
            write_ascii(buf, cloud, layout);
            break;
        case PcdEncoding::kBinary:
            write_binary(buf, cloud, layout);
            break;
        case PcdEncoding::kBinaryCompressed:
            write_compressed(buf, cloud, layout);
            break;
    }
    buf.flush();
}

}  // namespace surfgrow::io
