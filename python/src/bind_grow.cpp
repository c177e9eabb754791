// surfgrow.grow and surfgrow.GrowResult.
#include <pybind11/stl.h>

#include <chrono>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "grown.hpp"
#include "progress.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::python {

namespace {

PlaneTest plane_test_named(const std::string& name) {
    if (name == "disk") return PlaneTest::kDisk;
    if (name == "paper") return PlaneTest::kPaper;
    invalid(cat({"plane_test '", name, "' is not 'disk' or 'paper'"}));
}

// Per-surface columns: (S, 3) or (S,) arrays, in the input's coordinates (offset added back).
template <class F>
py::array_t<double> surface_rows(const Grown& g, F&& f) {
    const auto& s = g.result.surfaces;
    return rows3(s.size(), [&](std::size_t i) { return f(s[i]); });
}

}  // namespace

SharedCloud cloud_for(const Grown& grown, const py::handle& points) {
    if (points.is_none()) return grown.cloud;
    SharedCloud c = HeldCloud::hold(points, "points");
    if (c->view().size() != grown.cloud->view().size())
        invalid(cat({"points has ", std::to_string(c->view().size()),
                     " rows but the result was grown from ",
                     std::to_string(grown.cloud->view().size()), " points"}));
    return c;
}

py::object to_python(const nlohmann::json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

void bind_grow(py::module_& m) {
    py::class_<Grown, std::shared_ptr<Grown>>(
        m, "GrowResult",
        "Surfaces grown over a cloud: per-surface arrays (S rows, surface id = row), a label per "
        "input point, and the run's statistics. Positions are in the input's units and "
        "coordinates.")
        .def("__len__", [](const Grown& g) { return g.result.surfaces.size(); })
        .def(
            "__repr__",
            [](const Grown& g) {
                const GrowStats& s = g.result.stats;
                return cat({"<surfgrow.GrowResult: ", std::to_string(s.points_in), " points -> ",
                            std::to_string(s.surfaces), " surfaces, ",
                            num(std::round(1000 * s.registered_fraction()) / 10), "% registered>"});
            })
        .def_property_readonly(
            "labels",
            [](py::object self) {
                const auto& g = self.cast<const Grown&>();
                return view(g.result.labels.data(),
                            {static_cast<py::ssize_t>(g.result.labels.size())}, self);
            },
            "(N,) int32: the surface of every input point, in input order; -1 unregistered "
            "(noise, NaN, outside the crop). A read-only view, not a copy.")
        .def_property_readonly(
            "normals",
            [](const Grown& g) {
                return surface_rows(g, [](const Surface& s) { return s.normal; });
            },
            "(S, 3) float64 unit normals, facing the sensor side")
        .def_property_readonly(
            "homes",
            [](const Grown& g) {
                return surface_rows(
                    g, [&](const Surface& s) { return Vec3d(s.home + g.cloud->view().offset); });
            },
            "(S, 3) float64: the home point each surface grew from")
        .def_property_readonly(
            "centroids",
            [](const Grown& g) {
                return surface_rows(g, [&](const Surface& s) {
                    return Vec3d(s.centroid + g.cloud->view().offset);
                });
            },
            "(S, 3) float64: centroid of each neighbourhood; its plane passes here")
        .def_property_readonly(
            "planes",
            [](const Grown& g) {
                const auto& s = g.result.surfaces;
                return plane_rows(s.size(), [&](std::size_t i) {
                    return std::pair{s[i].normal, Vec3d(s[i].centroid + g.cloud->view().offset)};
                });
            },
            "(S, 4) float64 planes (a, b, c, d): n . x + d = 0, n the unit normal")
        .def_property_readonly(
            "eigenvalues",
            [](const Grown& g) {
                return surface_rows(g, [](const Surface& s) { return s.eigenvalues; });
            },
            "(S, 3) float64 covariance eigenvalues, ascending [units^2]")
        .def_property_readonly(
            "radii",
            [](const Grown& g) {
                return column<double>(g.result.surfaces.size(),
                                      [&](std::size_t i) { return g.result.surfaces[i].radius; });
            },
            "(S,) float64: neighbourhood radius (mu, or larger where it adapted)")
        .def_property_readonly(
            "counts",
            [](const Grown& g) {
                return column<std::uint32_t>(g.result.surfaces.size(), [&](std::size_t i) {
                    return g.result.surfaces[i].point_count;
                });
            },
            "(S,) uint32: member points of each surface")
        .def_property_readonly(
            "mean_residuals",
            [](const Grown& g) {
                return column<double>(g.result.surfaces.size(), [&](std::size_t i) {
                    return g.result.surfaces[i].mean_residual;
                });
            },
            "(S,) float64: mean |distance| of the members to the plane")
        .def_property_readonly(
            "tolerances",
            [](const Grown& g) {
                return column<double>(g.result.surfaces.size(), [&](std::size_t i) {
                    return g.result.surfaces[i].tolerance;
                });
            },
            "(S,) float64: largest distance of a member from the plane")
        .def_property_readonly(
            "cloud", [](const Grown& g) { return g.cloud->cloud(); },
            "The Cloud it was grown from: shared when a Cloud was passed, else a Cloud copied from "
            "the array on first use")
        .def_property_readonly(
            "parameters", [](const Grown& g) { return to_python(io::parameters_json(g.config)); },
            "Every parameter used, defaults resolved (as in surfaces.json)")
        .def_property_readonly(
            "summary",
            [](const Grown& g) {
                py::dict d = to_python(io::summary_json(g.result.stats));
                const StageTimes& t = g.result.stats.seconds;
                py::dict seconds;
                seconds["index"] = t.index;
                seconds["grow"] = t.grow;
                seconds["attach"] = t.attach;
                seconds["finish"] = t.finish;
                seconds["total"] = t.total();
                seconds["call"] = g.call_seconds;
                d["seconds"] = seconds;
                return d;
            },
            "dict: points in, valid, surfaces, registered share (registered_fraction), data "
            "reduction, rejected home points, registration by range band, the noise measured by "
            "range, and seconds per stage ('call': the whole library call)");

    m.def(
        "grow",
        [](const py::object& points, double mu, int min_pts, std::uint64_t seed, int threads,
           double alpha, const std::string& plane_test, double min_spread, double max_incidence_deg,
           double thickness_sigmas, double noise_sigmas, int min_new_points, double plane_tolerance,
           double adaptive_factor, bool attach_leftovers, double pool_angle_deg, double pool_radius,
           const py::object& viewpoint, const py::object& crop_box, const py::object& crop_radius,
           const py::object& crop_center, double range_band, const py::object& progress,
           bool copy) {
            auto g = std::make_shared<Grown>();
            GrowerConfig& c = g->config;
            c.mu = mu;
            c.min_pts = min_pts;
            c.seed = seed;
            c.threads = threads;
            c.alpha = alpha;
            c.plane_test = plane_test_named(plane_test);
            c.min_spread = min_spread;
            c.max_incidence_deg = max_incidence_deg;
            c.thickness_sigmas = thickness_sigmas;
            c.noise_sigmas = noise_sigmas;
            c.min_new_points = min_new_points;
            c.plane_tolerance = plane_tolerance;
            c.adaptive_factor = adaptive_factor;
            c.attach_leftovers = attach_leftovers;
            c.pool_angle_deg = pool_angle_deg;
            c.pool_radius = pool_radius;
            c.range_band = range_band;
            g->cloud = HeldCloud::hold(points, "points", copy);
            const Vec3d& offset = g->cloud->view().offset;  // the library works relative to it
            if (auto v = optional_vec3(viewpoint, "viewpoint")) c.viewpoint = *v - offset;
            if (!crop_box.is_none()) {
                const auto rows = rows3_from(crop_box, "crop_box");
                if (rows.size() != 2) invalid("crop_box must be 2 rows: (min, max)");
                Aabb box;
                box.min = rows[0] - offset;
                box.max = rows[1] - offset;
                c.crop.box = box;
            }
            if (!crop_radius.is_none()) c.crop.radius = crop_radius.cast<double>();
            if (auto v = optional_vec3(crop_center, "crop_center")) c.crop.center = *v - offset;
            validate(c);

            ProgressHook hook(progress);
            GrowerConfig with_progress = c;
            with_progress.progress = hook.function();
            const SurfaceGrower grower(with_progress);
            const auto start = std::chrono::steady_clock::now();
            g->result = hook.run([&] { return grower.grow(g->cloud->view()); });
            g->call_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const GrowStats& st = g->result.stats;
            if (st.sparse_for_mu()) {
                const std::string message = cat(
                    {"only ", std::to_string(static_cast<int>(100 * st.registered_fraction())),
                     "% registered: ", std::to_string(st.rejected_sparse),
                     " home points had fewer than ", std::to_string(c.min_pts),
                     " neighbours within mu = ", num(c.mu),
                     ". Points are too far apart for mu, or mu is not in the cloud's units "
                     "(0.012 is 12 mm in metres): try a larger mu or adaptive_factor, or crop to "
                     "the workspace"});
                if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0)
                    throw py::error_already_set();
            }
            return g;
        },
        py::arg("points"), py::arg("mu") = 0.012, py::arg("min_pts") = 10, py::arg("seed") = 1,
        py::arg("threads") = 0, py::kw_only(), py::arg("alpha") = 4.0,
        py::arg("plane_test") = "disk", py::arg("min_spread") = 0.3,
        py::arg("max_incidence_deg") = 85.0, py::arg("thickness_sigmas") = 2.5,
        py::arg("noise_sigmas") = 4.0, py::arg("min_new_points") = 1,
        py::arg("plane_tolerance") = 0.0, py::arg("adaptive_factor") = 8.0,
        py::arg("attach_leftovers") = true, py::arg("pool_angle_deg") = 15.0,
        py::arg("pool_radius") = 0.0, py::arg("viewpoint") = py::none(),
        py::arg("crop_box") = py::none(), py::arg("crop_radius") = py::none(),
        py::arg("crop_center") = py::none(), py::arg("range_band") = 1.0,
        py::arg("progress") = py::none(), py::arg("copy") = false,
        "Grows surfaces over `points`: an (N, 3) float32/float64 array in the cloud's units, or "
        "a Cloud (which also carries the viewpoint or scan origins that orient normals). mu is "
        "the cube side and neighbourhood radius in those units (default 0.012: metres). Same "
        "points, parameters and seed give the same result for any thread count. The GIL is "
        "released while it runs; Ctrl-C stops it. progress: None, or a callable (stage, "
        "fraction). A C-ordered float32 array is read in place, not copied, and the result keeps "
        "a reference to it for later calls (bound_planes, occupancy): do not change it "
        "afterwards, or pass copy=True; other arrays are converted once. Raises "
        "InvalidParameterError for a parameter out of range or a bad array.");
}

}  // namespace surfgrow::python
