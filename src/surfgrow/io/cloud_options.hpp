// What the point-cloud readers and writers can be asked to do.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace surfgrow::io {

/// The point-cloud file formats surfgrow reads and writes.
enum class CloudFormat {
    kPly,   ///< Stanford PLY (.ply)
    kPcd,   ///< PCL's Point Cloud Data, v0.7 and v0.6 (.pcd)
    kText,  ///< one point per line (.xyz, .txt, .csv, .pts)
};

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };
enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

[[nodiscard]] std::string_view to_string(CloudFormat format);
[[nodiscard]] std::string_view to_string(PlyEncoding encoding);  ///< as in the PLY header
[[nodiscard]] std::string_view to_string(PcdEncoding encoding);  ///< as in the PCD DATA line

struct ReadOptions {
    /// Read as this format whatever the file's extension; nullopt: from the extension, or from
    /// the content when the extension is not a known one.
    std::optional<CloudFormat> format;
    /// Read the integer field `label_field` (PLY property, PCD field, text header column) into
    /// PointCloud::labels when the file has one.
    bool read_labels = true;
    std::string label_field = "label";
    /// Read per-point normals into PointCloud::normals when the file has all three of them, of
    /// any scalar type: PLY properties nx ny nz, PCD fields normal_x normal_y normal_z (COUNT 1),
    /// text header columns nx ny nz. A file with only some of them, or with one unusable (a PLY
    /// list, a PCD COUNT above 1), is read without normals.
    bool read_normals = true;
    /// PLY: read the scan each point came from (property "scan") and the scans' origins
    /// ("comment surfgrow scan_origin k x y z" header lines) into PointCloud::scan_index and
    /// scan_origins, so normals can face their own sensor. Files without those comments are
    /// read as before.
    bool read_scans = true;
};

/// What the commands read: points, labels and scans, not the normals they never use (12 bytes a
/// point, and time).
inline const ReadOptions kPointsOnly = [] {
    ReadOptions o;
    o.read_normals = false;
    return o;
}();

struct WriteOptions {
    /// Write this format whatever the extension; nullopt: from the extension.
    std::optional<CloudFormat> format;
    PlyEncoding ply_encoding = PlyEncoding::kBinaryLittleEndian;
    PcdEncoding pcd_encoding = PcdEncoding::kBinary;
    /// PLY and PCD: write PointCloud::labels (property / field "label") when the cloud has them.
    bool write_labels = true;
    /// Write PointCloud::normals when the cloud has them, as float: PLY properties nx ny nz and
    /// PCD fields normal_x normal_y normal_z after x y z, text columns 4-6 under a header row
    /// "x y z nx ny nz". A cloud whose normals are not one per point is refused either way.
    bool write_normals = true;
    /// Text: add the labels as a last column, under a header row "x y z label" (or
    /// "x y z nx ny nz label" with normals).
    bool text_labels = false;
    /// PLY: write PointCloud::scan_index as "property uint scan" and scan_origins as header
    /// comments, when the cloud has them (other formats never carry them).
    bool write_scans = false;
};

}  // namespace surfgrow::io
