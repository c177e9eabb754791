// Writing PLY: one vertex element, float or double x y z, optional float nx ny nz, int label and
// uint scan.
#include "surfgrow/io/cloud_layout.hpp"
#include "surfgrow/io/output_buffer.hpp"
#include "surfgrow/io/ply.hpp"

namespace surfgrow::io {

namespace {

// Whether to write the scan index; a scan index beyond the origins is a bug in the caller.
bool scans_to_write(const CloudView& cloud, bool write_scans) {
    if (!write_scans || !cloud.has_scan_index() || cloud.scan_origins.empty()) return false;
    for (const std::uint32_t k : cloud.scan_index) {
        if (k >= cloud.scan_origins.size())
            throw Error(ErrorCode::kInternal,
                        cat({"cloud has scan index ", std::to_string(k), " but ",
                             std::to_string(cloud.scan_origins.size()), " scan origins"}));
    }
    return true;
}

}  // namespace

void write_ply(std::ostream& out, const CloudView& cloud, PlyEncoding encoding, bool write_labels,
               bool write_scans, bool write_normals) {
    const CloudLayout layout = layout_for(cloud, write_labels, write_normals);
    const bool scans = scans_to_write(cloud, write_scans);
    const std::string_view type = layout.doubles ? "double" : "float";
    OutputBuffer buf(out);
    buf.append(cat({"ply\nformat ", to_string(encoding), " 1.0\ncomment written by surfgrow\n"}));
    for (std::size_t k = 0; scans && k < cloud.scan_origins.size(); ++k) {
        const Vec3d o = cloud.scan_origins[k] + cloud.offset;
        buf.append(cat({"comment surfgrow scan_origin ", std::to_string(k), " ", num(o.x()), " ",
                        num(o.y()), " ", num(o.z()), "\n"}));
    }
    buf.append(cat({"element vertex ", std::to_string(cloud.size()), "\nproperty ", type,
                    " x\nproperty ", type, " y\nproperty ", type, " z\n"}));
    if (layout.normals) buf.append("property float nx\nproperty float ny\nproperty float nz\n");
    if (layout.labels) buf.append("property int label\n");
    if (scans) buf.append("property uint scan\n");
    buf.append("end_header\n");

    const std::size_t n = cloud.size();
    if (encoding == PlyEncoding::kAscii) {
        for (std::size_t i = 0; i < n; ++i) {
            if (layout.doubles) {
                const Vec3d p = absolute_point(cloud, i);
                buf.put_number(p.x());
                buf.put(' ');
                buf.put_number(p.y());
                buf.put(' ');
                buf.put_number(p.z());
            } else {
                const Vec3f& p = cloud.points[i];
                buf.put_number(p.x());
                buf.put(' ');
                buf.put_number(p.y());
                buf.put(' ');
                buf.put_number(p.z());
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
            if (scans) {
                buf.put(' ');
                buf.put_number(cloud.scan_index[i]);
            }
            buf.put('\n');
        }
    } else {
        const bool big = encoding == PlyEncoding::kBinaryBigEndian;
        const bool swap = big == kHostIsLittleEndian;
        for (std::size_t i = 0; i < n; ++i) {
            if (layout.doubles) {
                const Vec3d p = absolute_point(cloud, i);
                for (int a = 0; a < 3; ++a) buf.put_binary(p[a], swap);
            } else {
                for (int a = 0; a < 3; ++a) buf.put_binary(cloud.points[i][a], swap);
            }
            if (layout.normals) {
                for (int a = 0; a < 3; ++a) buf.put_binary(cloud.normals[i][a], swap);
            }
            if (layout.labels) buf.put_binary(cloud.labels[i], swap);
            if (scans) buf.put_binary(cloud.scan_index[i], swap);
        }
    }
    buf.flush();
}

}  // namespace surfgrow::io
