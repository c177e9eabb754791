// What surfgrow.GrowResult holds: the result, the cloud it was grown from and the configuration,
// so that later stages (planes, occupancy, evaluation) need nothing else.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "held_cloud.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"

namespace surfgrow::python {

struct Grown {
    SharedCloud cloud;    // read in place when it was a float32 array (HeldCloud)
    GrowerConfig config;  // without its progress callback
    GrowResult result;
    double call_seconds = 0.0;  // the library call, GIL released: what C++ would take
};

/// The cloud a later stage works on: `points` when given (an array or a Cloud of the same point
/// count), else the grown one.
[[nodiscard]] SharedCloud cloud_for(const Grown& grown, const pybind11::handle& points);

/// JSON (the library's report formats) as Python dicts and lists.
[[nodiscard]] pybind11::object to_python(const nlohmann::json& j);

}  // namespace surfgrow::python
