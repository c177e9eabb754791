// surfgrow.Cloud, read_cloud, write_cloud.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::python {

namespace {

std::optional<io::CloudFormat> format_named(const std::optional<std::string>& name) {
    if (!name) return std::nullopt;
    if (*name == "ply") return io::CloudFormat::kPly;
    if (*name == "pcd") return io::CloudFormat::kPcd;
    if (*name == "text" || *name == "xyz") return io::CloudFormat::kText;
    throw Error(ErrorCode::kUsage, cat({"format '", *name, "' is not ply, pcd or text"}));
}

// A cloud from arrays, every per-point array checked against the point count.
std::shared_ptr<PointCloud> make_cloud(const py::handle& points, const py::handle& viewpoint,
                                       const py::handle& scan_index, const py::handle& scan_origins,
                                       const py::handle& labels, const py::handle& normals) {
    auto c = std::make_shared<PointCloud>(cloud_from_points(points));
    const std::size_t n = c->size();
    if (auto v = optional_vec3(viewpoint, "viewpoint")) c->viewpoint = *v - c->offset;
    const auto per_point = [&](std::size_t size, const char* what) {
        if (size != n)
            invalid(cat({what, " has ", std::to_string(size), " entries for ", std::to_string(n),
                         " points"}));
    };
    if (!scan_origins.is_none()) {
        c->scan_origins = rows3_from(scan_origins, "scan_origins");
        for (Vec3d& o : c->scan_origins) o -= c->offset;
        if (scan_index.is_none()) invalid("scan_origins needs scan_index (the scan of each point)");
    }
    if (!scan_index.is_none()) {
        if (c->scan_origins.empty()) invalid("scan_index needs scan_origins (one per scan)");
        c->scan_index = ints_from<std::uint32_t>(
            scan_index, "scan_index", 0, static_cast<std::int64_t>(c->scan_origins.size()) - 1);
        per_point(c->scan_index.size(), "scan_index");
    }
    if (!labels.is_none()) {
        c->labels = ints_from<std::int32_t>(labels, "labels", INT32_MIN, INT32_MAX);
        per_point(c->labels.size(), "labels");
    }
    if (!normals.is_none()) {
        const PointCloud nc = cloud_from_points(normals, "normals");
        if (nc.offset != Vec3d::Zero()) invalid("normals must be unit vectors");
        c->normals = nc.points;
        per_point(c->normals.size(), "normals");
    }
    return c;
}

}  // namespace

void bind_cloud(py::module_& m) {
    py::class_<PointCloud, std::shared_ptr<PointCloud>>(
        m, "Cloud",
        "A point cloud in its own units, with what is known about its scans: the sensor "
        "viewpoint, or the scan each point came from and the scans' origins (fused clouds), and "
        "optional per-point labels and normals. Arrays it returns are read-only views.")
        .def(py::init(&make_cloud), py::arg("points"), py::kw_only(),
             py::arg("viewpoint") = py::none(), py::arg("scan_index") = py::none(),
             py::arg("scan_origins") = py::none(), py::arg("labels") = py::none(),
             py::arg("normals") = py::none(),
             "points: (N, 3) float32 or float64. viewpoint: (3,) sensor origin of a single scan. "
             "scan_index: (N,) scan of each point; scan_origins: (K, 3) each scan's sensor "
             "origin. labels: (N,) int32. normals: (N, 3). One copy of each array is made.")
        .def("__len__", &PointCloud::size)
        .def("__repr__",
             [](const PointCloud& c) {
                 return cat({"<surfgrow.Cloud: ", std::to_string(c.size()), " points",
                             c.has_scan_index()
                                 ? cat({", ", std::to_string(c.scan_origins.size()), " scans"})
                                 : "",
                             c.has_labels() ? ", labels" : "", ">"});
             })
        .def_property_readonly(
            "points",
            [](py::object self) {
                const auto& c = self.cast<const PointCloud&>();
                return view(c.points.empty() ? nullptr : c.points.front().data(),
                            {static_cast<py::ssize_t>(c.size()), 3}, self);
            },
            "(N, 3) float32, relative to `offset` (zero but for georeferenced clouds); NaN rows "
            "are points the sensor missed")
        .def_property_readonly(
            "offset", [](const PointCloud& c) { return vec3_array(c.offset); },
            "(3,) float64: add to `points` for the file's coordinates")
        .def_property_readonly(
            "viewpoint",
            [](const PointCloud& c) -> py::object {
                if (!c.viewpoint) return py::none();
                return vec3_array(Vec3d(*c.viewpoint + c.offset));
            },
            "(3,) sensor origin of the whole cloud (the input's coordinates), or None")
        .def_property_readonly(
            "scan_index",
            [](py::object self) -> py::object {
                const auto& c = self.cast<const PointCloud&>();
                if (!c.has_scan_index()) return py::none();
                return view(c.scan_index.data(), {static_cast<py::ssize_t>(c.size())}, self);
            },
            "(N,) uint32: the scan each point came from, or None")
        .def_property_readonly(
            "scan_origins",
            [](const PointCloud& c) -> py::object {
                if (c.scan_origins.empty()) return py::none();
                return rows3(c.scan_origins.size(),
                             [&](std::size_t k) { return Vec3d(c.scan_origins[k] + c.offset); });
            },
            "(K, 3) float64: each scan's sensor origin (the input's coordinates), or None")
        .def_property_readonly(
            "labels",
            [](py::object self) -> py::object {
                const auto& c = self.cast<const PointCloud&>();
                if (!c.has_labels()) return py::none();
                return view(c.labels.data(), {static_cast<py::ssize_t>(c.size())}, self);
            },
            "(N,) int32 labels from the file (e.g. ground-truth faces), or None")
        .def_property_readonly(
            "normals",
            [](py::object self) -> py::object {
                const auto& c = self.cast<const PointCloud&>();
                if (!c.has_normals()) return py::none();
                return view(c.normals.front().data(), {static_cast<py::ssize_t>(c.size()), 3},
                            self);
            },
            "(N, 3) float32 normals from the file, or None");

    m.def(
        "read_cloud",
        [](const std::filesystem::path& path, const std::optional<std::string>& format,
           const std::string& label_field) {
            io::ReadOptions o;
            o.format = format_named(format);
            o.label_field = label_field;
            py::gil_scoped_release release;
            return std::make_shared<PointCloud>(io::read_cloud(path, o));
        },
        py::arg("path"), py::kw_only(), py::arg("format") = py::none(),
        py::arg("label_field") = "label",
        "Reads a PLY, PCD (ascii, binary, binary_compressed) or text cloud. The format comes from "
        "`format` ('ply', 'pcd', 'text'), else the extension, else the content. Units are the "
        "file's. Raises CannotOpenError, UnknownFormatError or MalformedInputError naming the "
        "file.");

    m.def(
        "write_cloud",
        [](const std::filesystem::path& path, const py::object& points, const py::object& normals,
           const py::object& labels, const std::optional<std::string>& format,
           const std::optional<std::string>& encoding) {
            std::shared_ptr<const PointCloud> cloud;
            if (py::isinstance<PointCloud>(points) && normals.is_none() && labels.is_none()) {
                cloud = points.cast<std::shared_ptr<PointCloud>>();
            } else {
                auto c =
                    make_cloud(py::isinstance<PointCloud>(points) ? points.attr("points") : points,
                               py::none(), py::none(), py::none(), labels, normals);
                if (py::isinstance<PointCloud>(points)) {
                    const auto& src = points.cast<const PointCloud&>();
                    c->offset = src.offset;
                    c->viewpoint = src.viewpoint;
                    c->scan_index = src.scan_index;
                    c->scan_origins = src.scan_origins;
                    if (labels.is_none()) c->labels = src.labels;
                    if (normals.is_none()) c->normals = src.normals;
                }
                cloud = std::move(c);
            }
            io::WriteOptions o;
            o.format = format_named(format);
            o.write_scans = true;  // a fused cloud keeps its scans (PLY), so it reads back the same
            if (encoding) {
                const std::string& e = *encoding;
                if (e == "ascii") {
                    o.ply_encoding = io::PlyEncoding::kAscii;
                    o.pcd_encoding = io::PcdEncoding::kAscii;
                } else if (e == "binary" || e == "binary_little_endian") {
                    o.ply_encoding = io::PlyEncoding::kBinaryLittleEndian;
                    o.pcd_encoding = io::PcdEncoding::kBinary;
                } else if (e == "binary_big_endian") {
                    o.ply_encoding = io::PlyEncoding::kBinaryBigEndian;
                } else if (e == "binary_compressed") {
                    o.pcd_encoding = io::PcdEncoding::kBinaryCompressed;
                } else {
                    throw Error(ErrorCode::kUsage,
                                cat({"encoding '", e,
                                     "' is not ascii, binary, binary_little_endian, "
                                     "binary_big_endian or binary_compressed"}));
                }
            }
            py::gil_scoped_release release;
            io::write_cloud(path, *cloud, o);
        },
        py::arg("path"), py::arg("points"), py::kw_only(), py::arg("normals") = py::none(),
        py::arg("labels") = py::none(), py::arg("format") = py::none(),
        py::arg("encoding") = py::none(),
        "Writes points (an (N, 3) array or a Cloud) with optional (N, 3) normals and (N,) int32 "
        "labels, atomically (a temporary renamed into place). The format comes from `format` or "
        "the extension (.ply, .pcd, .xyz/.txt/.csv/.pts); binary by default.");
}

}  // namespace surfgrow::python
