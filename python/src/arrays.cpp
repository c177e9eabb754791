#include "arrays.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/point_builder.hpp"

namespace surfgrow::python {

namespace {

std::string shape_of(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) {
        if (k) s += ", ";
        s += std::to_string(a.shape(k));
    }
    return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_of(const py::array& a) {
    return py::str(a.dtype()).cast<std::string>();
}

py::array as_array(const py::handle& v, const char* what) {
    if (v.is_none()) invalid(cat({what, " is None"}));
    py::array a = py::array::ensure(v);
    if (!a) invalid(cat({what, " must be an array of numbers"}));
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        invalid(cat({what, " must hold real numbers (float32 or float64), not ", dtype_of(a)}));
    return a;
}

}  // namespace

PointCloud cloud_from_points(const py::handle& points, const char* what) {
    const py::array a = as_array(points, what);
    if (a.ndim() != 2 || a.shape(1) != 3)
        invalid(cat({what, " must have shape (N, 3), not ", shape_of(a),
                     a.ndim() == 2 && a.shape(1) > 3 ? ": pass points[:, :3]" : ""}));
    const auto n = static_cast<std::size_t>(a.shape(0));
    PointCloud cloud;
    cloud.points.resize(n);
    if (py::isinstance<py::array_t<float>>(a) && a.dtype().kind() == 'f' && a.itemsize() == 4) {
        const auto* base = static_cast<const char*>(a.data());
        const py::ssize_t rs = a.strides(0), cs = a.strides(1);
        if (rs == 3 * 4 && cs == 4) {
            if (n) std::memcpy(static_cast<void*>(cloud.points.data()), base, n * sizeof(Vec3f));
        } else {
            for (std::size_t i = 0; i < n; ++i)
                for (py::ssize_t k = 0; k < 3; ++k)
                    std::memcpy(&cloud.points[i][k], base + py::ssize_t(i) * rs + k * cs, 4);
        }
        return cloud;
    }
    // Wider or integer types: one conversion to double, then the readers' offset rule.
    const auto d = py::array_t<double, py::array::forcecast>::ensure(a);
    const auto r = d.unchecked<2>();
    std::optional<Vec3d> offset;
    for (std::size_t i = 0; i < n && !offset; ++i) {
        const auto row = static_cast<py::ssize_t>(i);
        offset = io::offset_for(r(row, 0), r(row, 1), r(row, 2));
    }
    if (offset) cloud.offset = *offset;
    const Vec3d o = cloud.offset;
    for (std::size_t i = 0; i < n; ++i) {
        const auto row = static_cast<py::ssize_t>(i);
        cloud.points[i] =
            Vec3f(static_cast<float>(r(row, 0) - o.x()), static_cast<float>(r(row, 1) - o.y()),
                  static_cast<float>(r(row, 2) - o.z()));
    }
    return cloud;
}

Vec3d vec3_from(const py::handle& v, const char* what) {
    const auto d = py::array_t<double, py::array::forcecast>::ensure(as_array(v, what));
    if (d.size() != 3) invalid(cat({what, " must be 3 numbers (x, y, z), not ", shape_of(d)}));
    const Vec3d p(d.data()[0], d.data()[1], d.data()[2]);
    if (!p.allFinite()) invalid(cat({what, " must be finite"}));
    return p;
}

std::vector<Vec3d> rows3_from(const py::handle& v, const char* what) {
    const auto d = doubles_2d(v, what, 3);
    std::vector<Vec3d> out(static_cast<std::size_t>(d.shape(0)));
    const auto r = d.unchecked<2>();
    for (std::size_t i = 0; i < out.size(); ++i) {
        const auto row = static_cast<py::ssize_t>(i);
        out[i] = Vec3d(r(row, 0), r(row, 1), r(row, 2));
    }
    return out;
}

py::array_t<double, py::array::c_style> doubles_2d(const py::handle& v, const char* what,
                                                   py::ssize_t cols) {
    py::array a = as_array(v, what);
    if (a.ndim() == 1 && a.shape(0) == cols) a = a.attr("reshape")(1, cols);
    if (a.ndim() != 2 || a.shape(1) != cols)
        invalid(cat({what, " must have shape (M, ", std::to_string(cols), "), not ", shape_of(a)}));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    const double* p = d.data();
    for (py::ssize_t i = 0; i < d.size(); ++i)
        if (!std::isfinite(p[i]))
            invalid(cat({what, " row ", std::to_string(i / cols), " is not finite"}));
    return d;
}

template <class T>
std::vector<T> ints_from(const py::handle& v, const char* what, std::int64_t lo, std::int64_t hi) {
    const py::array a = as_array(v, what);
    if (a.ndim() != 1) invalid(cat({what, " must have shape (N,), not ", shape_of(a)}));
    if (a.dtype().kind() == 'f') invalid(cat({what, " must hold integers, not ", dtype_of(a)}));
    const auto d = py::array_t<std::int64_t, py::array::forcecast>::ensure(a);
    std::vector<T> out(static_cast<std::size_t>(d.size()));
    const auto r = d.unchecked<1>();
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::int64_t x = r(static_cast<py::ssize_t>(i));
        if (x < lo || x > hi)
            invalid(cat({what, "[", std::to_string(i), "] = ", std::to_string(x), " lies outside ",
                         std::to_string(lo), "..", std::to_string(hi)}));
        out[i] = static_cast<T>(x);
    }
    return out;
}

template std::vector<std::uint32_t> ints_from(const py::handle&, const char*, std::int64_t,
                                              std::int64_t);
template std::vector<std::int32_t> ints_from(const py::handle&, const char*, std::int64_t,
                                             std::int64_t);

}  // namespace surfgrow::python
