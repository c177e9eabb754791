// The parts of the module, each binding one area of the library. What they share: arrays.hpp
// (numpy conversions), held_cloud.hpp (the cloud a result refers to).
#pragma once

#include <pybind11/pybind11.h>

namespace surfgrow::python {

void bind_cloud(pybind11::module_& m);  // Cloud, read_cloud, write_cloud
void bind_grow(pybind11::module_& m);   // grow, GrowResult
void bind_robot(pybind11::module_& m);  // bound_planes, coverage, occupancy, CollisionSpheres
void bind_scan(pybind11::module_& m);   // simulate, Scan, Truth, evaluate
void bind_map(pybind11::module_& m);    // Map

}  // namespace surfgrow::python
