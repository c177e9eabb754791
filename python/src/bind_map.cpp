// surfgrow.Map: mapping scan by scan (pipeline/map.hpp), each scan's result a GrowResult that
// the other stages (bound_planes, coverage, occupancy, evaluate) take as they take grow's.
#include <pybind11/stl.h>

#include <chrono>
#include <memory>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "grown.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/pipeline/map.hpp"

namespace surfgrow::python {

namespace {

// The growing's map only: Python runs the robot outputs as stages of its own, on demand.
MapConfig growing_only(double mu, int min_pts, std::uint64_t seed, int threads,
                       double join_tolerance) {
    MapConfig c;
    c.pipeline.grow.mu = mu;
    c.pipeline.grow.min_pts = min_pts;
    c.pipeline.grow.seed = seed;
    c.pipeline.grow.threads = threads;
    c.pipeline.planes = std::nullopt;
    c.pipeline.coverage = std::nullopt;
    c.pipeline.occupancy = false;
    c.pipeline.collision = false;
    c.join_tolerance = join_tolerance;
    return c;
}

}  // namespace

void bind_map(py::module_& m) {
    py::class_<Map, std::shared_ptr<Map>>(
        m, "Map",
        "A map grown scan by scan, as the scans arrive: each scan's points join the surfaces "
        "already mapped where they fit and grow new ones elsewhere, so adding scan k costs about "
        "the growing of scan k alone. Deterministic for a given order of scans and seed.")
        .def(py::init([](double mu, int min_pts, std::uint64_t seed, int threads,
                         double join_tolerance) {
                 return std::make_shared<Map>(
                     growing_only(mu, min_pts, seed, threads, join_tolerance));
             }),
             py::arg("mu") = 0.012, py::arg("min_pts") = 10, py::arg("seed") = 1,
             py::arg("threads") = 0, py::kw_only(), py::arg("join_tolerance") = 1.5,
             "mu in the scans' units (default 0.012: metres). join_tolerance: a new point joins a "
             "mapped surface within this many times the surface's tolerance of its plane (1..10)")
        .def(
            "add_scan",
            [](Map& map, const py::object& points, const py::object& origin) {
                const SharedCloud scan = HeldCloud::hold(points, "points");
                const Vec3d o = vec3_from(origin, "origin") - scan->view().offset;
                auto g = std::make_shared<Grown>();
                const auto start = std::chrono::steady_clock::now();
                {
                    py::gil_scoped_release release;
                    (void)map.add_scan(scan->view(), o);
                }
                g->call_seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                // A snapshot: later scans leave this result as it was.
                g->cloud =
                    HeldCloud::hold(py::cast(std::make_shared<PointCloud>(map.cloud())), "map");
                g->config = map.pipeline_config().grow;
                g->config.progress = nullptr;
                g->result = map.result().grow;
                return g;
            },
            py::arg("points"), py::arg("origin"),
            "Adds one scan: (N, 3) points (or a Cloud) in the map's frame and units, taken from "
            "`origin` (3,). Returns the whole map so far as a GrowResult (its cloud: every scan's "
            "points in order, each with its scan and the scans' origins).")
        .def_property_readonly("scans", &Map::scans, "scans added so far")
        .def_property_readonly(
            "last_update",
            [](const Map& map) {
                const MapUpdate& u = map.last_update();
                py::dict d;
                d["scan"] = u.scan;
                d["points"] = u.points;
                d["joined"] = u.joined;
                d["grown"] = u.grown;
                d["new_surfaces"] = u.new_surfaces;
                d["join_seconds"] = u.join_seconds;
                d["grow_seconds"] = u.grow_seconds;
                return d;
            },
            "dict of the last add_scan: its points, how many joined mapped surfaces, how many "
            "grew new ones, and seconds")
        .def("__repr__", [](const Map& map) {
            return cat({"<surfgrow.Map: ", std::to_string(map.scans()), " scans, ",
                        std::to_string(map.cloud().size()), " points, ",
                        std::to_string(map.result().grow.surfaces.size()), " surfaces>"});
        });
}

}  // namespace surfgrow::python
