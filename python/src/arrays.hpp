// Between numpy arrays and the library's types: at most one copy in, never a Python object per
// point; views out where the library's vectors can be kept alive by their Python owner.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow::python {

namespace py = pybind11;

/// Throws Error(kInvalidParameter): InvalidParameterError in Python.
[[noreturn]] inline void invalid(const std::string& message) {
    throw Error(ErrorCode::kInvalidParameter, message);
}

/// An (N, 3) array of points as a PointCloud. float32 rows are taken as they are (one memcpy
/// when C-contiguous, one strided copy otherwise); float64 and integer rows are converted once,
/// with the file readers' offset rule (coordinates beyond 1e4 are stored relative to a rounded
/// offset, PointCloud::offset). NaN/Inf rows are kept: the library skips them. Throws
/// Error(kInvalidParameter) naming `what` for another shape or a non-numeric dtype.
[[nodiscard]] PointCloud cloud_from_points(const py::handle& points, const char* what = "points");

/// A (3,) vector of finite numbers. Throws Error(kInvalidParameter) naming `what`.
[[nodiscard]] Vec3d vec3_from(const py::handle& v, const char* what);
/// (K, 3) rows (or one (3,) vector as one row) of finite numbers.
[[nodiscard]] std::vector<Vec3d> rows3_from(const py::handle& v, const char* what);
/// An (N,) array of integers in [lo, hi], as `T`.
template <class T>
[[nodiscard]] std::vector<T> ints_from(const py::handle& v, const char* what, std::int64_t lo,
                                       std::int64_t hi);
/// A (rows, cols) array of float64 (one copy), checked finite.
[[nodiscard]] py::array_t<double, py::array::c_style> doubles_2d(const py::handle& v,
                                                                 const char* what,
                                                                 py::ssize_t cols);

/// A numpy array over `data` (not copied), kept alive by `owner`; read-only.
template <class T>
[[nodiscard]] py::array view(const T* data, std::vector<py::ssize_t> shape, py::handle owner) {
    py::array a(py::dtype::of<T>(), std::move(shape), data, owner);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return a;
}

/// An (n, 3) float64 array with row i = f(i).
template <class F>
[[nodiscard]] py::array_t<double> rows3(std::size_t n, F&& f) {
    py::array_t<double> a({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d p = f(i);
        for (py::ssize_t k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = p[k];
    }
    return a;
}

/// An (n,) array of T with element i = f(i).
template <class T, class F>
[[nodiscard]] py::array_t<T> column(std::size_t n, F&& f) {
    py::array_t<T> a(static_cast<py::ssize_t>(n));
    T* out = a.mutable_data();
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<T>(f(i));
    return a;
}

/// A (3,) float64 array.
[[nodiscard]] inline py::array_t<double> vec3_array(const Vec3d& p) {
    py::array_t<double> a(3);
    for (py::ssize_t k = 0; k < 3; ++k) a.mutable_data()[k] = p[k];
    return a;
}

/// An (n, 4) float64 array of planes (a, b, c, d), n . x + d = 0, from each one's unit normal
/// and a point on it (both given by f(i) as a pair).
template <class F>
[[nodiscard]] py::array_t<double> plane_rows(std::size_t n, F&& f) {
    py::array_t<double> a({static_cast<py::ssize_t>(n), py::ssize_t{4}});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < n; ++i) {
        const auto [normal, point] = f(i);
        const auto r = static_cast<py::ssize_t>(i);
        for (py::ssize_t k = 0; k < 3; ++k) w(r, k) = normal[k];
        w(r, 3) = -normal.dot(point);
    }
    return a;
}

/// Optional (3,) vector: None gives nullopt.
[[nodiscard]] inline std::optional<Vec3d> optional_vec3(const py::handle& v, const char* what) {
    if (v.is_none()) return std::nullopt;
    return vec3_from(v, what);
}

}  // namespace surfgrow::python
