// Writing PLY: one vertex element, float or double x y z, optional int label.
#include "surfgrow/io/cloud_layout.hpp"
#include "surfgrow/io/output_buffer.hpp"
#include "surfgrow/io/ply.hpp"

namespace surfgrow::io {

void write_ply(std::ostream& out, const PointCloud& cloud, PlyEncoding encoding,
               bool write_labels) {
    const CloudLayout layout = layout_for(cloud, write_labels);
    const std::string_view type = layout.doubles ? "double" : "float";
    OutputBuffer buf(out);
    buf.append(
        cat({"ply\nformat ", to_string(encoding),
             " 1.0\ncomment written by surfgrow\nelement vertex ", std::to_string(cloud.size()),
             "\nproperty ", type, " x\nproperty ", type, " y\nproperty ", type, " z\n"}));
    if (layout.labels) buf.append("property int label\n");
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
            if (layout.labels) {
                buf.put(' ');
                buf.put_number(cloud.labels[i]);
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
            if (layout.labels) buf.put_binary(cloud.labels[i], swap);
        }
    }
    buf.flush();
}

}  // namespace surfgrow::io
