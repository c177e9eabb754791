#include "held_cloud.hpp"

#include <pybind11/numpy.h>

#include <cstdint>
#include <string>

#include "arrays.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::python {

namespace {

// Whether the library can read `points` where it lies: the layout of std::vector<Vec3f>.
bool readable_in_place(const py::handle& points) {
    if (!py::isinstance<py::array_t<float, py::array::c_style>>(points)) return false;
    const auto a = py::reinterpret_borrow<py::array>(points);
    if (a.ndim() != 2 || a.shape(1) != 3 || a.strides(1) != sizeof(float)) return false;
    if (a.shape(0) > 1 && a.strides(0) != static_cast<py::ssize_t>(sizeof(Vec3f))) return false;
    return reinterpret_cast<std::uintptr_t>(a.data()) % alignof(Vec3f) == 0;
}

}  // namespace

SharedCloud HeldCloud::hold(const py::handle& points, const char* what, bool copy) {
    std::shared_ptr<HeldCloud> h(new HeldCloud());
    if (py::isinstance<PointCloud>(points)) {
        h->owned_ = points.cast<std::shared_ptr<PointCloud>>();
        h->view_ = *h->owned_;
    } else if (!copy && readable_in_place(points)) {
        h->borrowed_ = py::reinterpret_borrow<py::object>(points);
        const auto a = py::reinterpret_borrow<py::array>(points);
        h->view_ = CloudView(std::span<const Vec3f>(static_cast<const Vec3f*>(a.data()),
                                                    static_cast<std::size_t>(a.shape(0))));
    } else {
        h->owned_ = std::make_shared<const PointCloud>(cloud_from_points(points, what));
        h->view_ = *h->owned_;
    }
    return h;
}

SharedCloud HeldCloud::with_origins(SharedCloud held, std::vector<Vec3d> origins) {
    const CloudView& v = held->view();
    if (origins.empty()) invalid("origins is empty: give one (3,) origin, or one per scan");
    if (origins.size() > 1) {
        if (!v.has_scan_index())
            invalid(
                "several origins need a cloud with scan_index (the scan of each point): pass a "
                "Cloud, or one origin");
        if (origins.size() != v.scan_origins.size())
            invalid(cat({"origins has ", std::to_string(origins.size()), " rows for a cloud of ",
                         std::to_string(v.scan_origins.size()), " scans"}));
    }
    std::shared_ptr<HeldCloud> h(new HeldCloud());
    h->view_ = v;
    h->origins_ = std::move(origins);
    if (h->origins_.size() == 1) {
        h->view_.viewpoint = h->origins_[0];
        h->view_.scan_index = {};
        h->view_.scan_origins = {};
    } else {
        h->view_.scan_origins = h->origins_;
    }
    h->base_ = std::move(held);
    return h;
}

HeldCloud::~HeldCloud() {
    // The last owner may let go without the GIL (a shared_ptr dropped in C++).
    if (borrowed_) {
        const py::gil_scoped_acquire gil;
        borrowed_ = py::object();
    }
}

std::shared_ptr<PointCloud> HeldCloud::cloud() const {
    if (owned_) return std::const_pointer_cast<PointCloud>(owned_);
    if (!as_cloud_) as_cloud_ = std::make_shared<PointCloud>(to_point_cloud(view_));
    return as_cloud_;
}

}  // namespace surfgrow::python
