// The parts of the module, each binding one area of the library; and the one conversion they
// share, from whatever a user passes as a cloud.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>

#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow::python {

void bind_cloud(pybind11::module_& m);  // Cloud, read_cloud, write_cloud
void bind_grow(pybind11::module_& m);   // grow, GrowResult
void bind_robot(pybind11::module_& m);  // bound_planes, coverage, occupancy, CollisionSpheres
void bind_scan(pybind11::module_& m);   // simulate, Scan, Truth, evaluate

/// A surfgrow.Cloud as it is (shared, not copied), or an (N, 3) array as a new cloud (one
/// copy: arrays.hpp).
[[nodiscard]] std::shared_ptr<const PointCloud> shared_cloud(const pybind11::handle& cloud,
                                                             const char* what = "points");

}  // namespace surfgrow::python
