// surfgrow._surfgrow: the library for Python (docs/python.md). The package surfgrow re-exports
// it with a few pure-Python helpers.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "errors.hpp"
#include "surfgrow/version.hpp"

PYBIND11_MODULE(_surfgrow, m) {
    m.doc() =
        "surfgrow: laser-scan point clouds to oriented surface patches, bound planes, "
        "coverage goals, occupancy and collision models. Lengths are in the cloud's units.";
    m.attr("__version__") = SURFGROW_VERSION;
    surfgrow::python::bind_errors(m);
    surfgrow::python::bind_cloud(m);
    surfgrow::python::bind_grow(m);
    surfgrow::python::bind_robot(m);
    surfgrow::python::bind_scan(m);
    surfgrow::python::bind_map(m);
}
