// surfgrow.simulate (the scan simulator, with ground truth) and surfgrow.evaluate.
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <variant>

#include "arrays.hpp"
#include "bindings.hpp"
#include "grown.hpp"
#include "progress.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/random.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/report_json.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/scene_file.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"
#include "surfgrow/scanner/veil_filter.hpp"

namespace surfgrow::python {

namespace {

/// Ground truth of a simulated scan: the scene's faces and each point's true face.
struct Truth {
    std::shared_ptr<const scanner::Scene> scene;
    std::shared_ptr<const PointCloud> cloud;  // labels = true face id per point (-1: none)
};

struct Scan {
    std::shared_ptr<PointCloud> cloud;
    std::vector<scanner::Pose> poses;
    std::shared_ptr<const Truth> truth;
};

// A range limit in whole millimetres (0: the laser's own), as the scan format stores it.
std::uint16_t range_mm(const std::optional<double>& metres, const char* what) {
    if (!metres) return 0;
    const double mm = std::round(*metres * 1000.0);
    if (!(mm >= 1 && mm <= 65534))
        invalid(cat({what, " = ", num(*metres),
                     " m lies outside any sensor's limits (0.001 to 65.534 m)"}));
    return static_cast<std::uint16_t>(mm);
}

scanner::SceneDescription scene_named(const std::string& name) {
    if (name.ends_with(".json") || name.find('/') != std::string::npos)
        return io::read_scene_file(name);
    return scanner::builtin_scene(name);
}

}  // namespace

void bind_scan(py::module_& m) {
    py::class_<Truth, std::shared_ptr<Truth>>(
        m, "Truth", "Ground truth of a simulated scan: the scene's faces and each point's face.")
        .def_property_readonly(
            "labels",
            [](py::object self) {
                const auto& t = self.cast<const Truth&>();
                return view(t.cloud->labels.data(), {static_cast<py::ssize_t>(t.cloud->size())},
                            self);
            },
            "(N,) int32: the true face of every point (-1: a mixed pixel or nothing)")
        .def_property_readonly(
            "faces", [](const Truth& t) { return t.scene->faces().size(); },
            "number of faces in the scene");

    py::class_<Scan, std::shared_ptr<Scan>>(
        m, "Scan", "A simulated tilting-laser scan, fused from its poses, with ground truth.")
        .def("__len__", [](const Scan& s) { return s.cloud->size(); })
        .def_property_readonly(
            "cloud", [](const Scan& s) { return s.cloud; },
            "the fused Cloud (metres, world frame), with each point's scan and the scan origins")
        .def_property_readonly(
            "points", [](const Scan& s) { return py::object(py::cast(s.cloud).attr("points")); },
            "(N, 3) float32 metres: cloud.points")
        .def_property_readonly(
            "truth", [](const Scan& s) { return std::const_pointer_cast<Truth>(s.truth); })
        .def_property_readonly(
            "poses",
            [](const Scan& s) {
                py::array_t<double> a(
                    {static_cast<py::ssize_t>(s.poses.size()), py::ssize_t{4}, py::ssize_t{4}});
                auto w = a.mutable_unchecked<3>();
                for (std::size_t k = 0; k < s.poses.size(); ++k)
                    for (py::ssize_t i = 0; i < 4; ++i)
                        for (py::ssize_t j = 0; j < 4; ++j)
                            w(static_cast<py::ssize_t>(k), i, j) = s.poses[k].matrix()(i, j);
                return a;
            },
            "(K, 4, 4) sensor-to-world pose of each scan");

    m.def(
        "simulate",
        [](const std::string& scene, const std::variant<int, std::string>& poses,
           std::uint64_t seed, int readings, int trim, const std::string& laser,
           const std::string& noise, double optical_offset, std::optional<double> min_range,
           std::optional<double> max_range, double veil_angle, const py::object& progress) {
            scanner::ScannerSpec spec;
            spec.laser = scanner::laser_preset(laser);
            spec.readings_per_ray = readings;
            spec.optical_offset_m = Vec3d(0, 0, optical_offset);
            spec.validate();
            scanner::NoiseModel model;
            if (noise == "ideal") {
                model = scanner::NoiseModel::ideal();
            } else if (noise != "datasheet") {
                invalid(cat({"noise '", noise, "' is not 'datasheet' or 'ideal'"}));
            }
            scanner::FuseOptions fuse;
            fuse.trim_q = trim;
            fuse.min_range_mm = range_mm(min_range, "min_range");
            fuse.max_range_mm = range_mm(max_range, "max_range");
            fuse.veil.angle_deg = veil_angle;
            scanner::validate(fuse.veil);
            auto truth = std::make_shared<Truth>();
            auto scene_ptr = std::make_shared<scanner::Scene>(scene_named(scene));
            truth->scene = scene_ptr;
            auto scan = std::make_shared<Scan>();
            if (const int* count = std::get_if<int>(&poses)) {
                scan->poses = scanner::scan_poses(scene_ptr->description().scanner, *count);
            } else {
                scan->poses = io::read_poses_file(std::get<std::string>(poses));
            }
            ProgressHook hook(progress);
            const scanner::ScanSimulator simulator(*scene_ptr, spec, model);
            scan->cloud = hook.run([&] {
                std::vector<scanner::RawScan> raws;
                for (std::size_t k = 0; k < scan->poses.size(); ++k) {
                    hook("simulate", double(k) / double(scan->poses.size()));
                    raws.push_back(simulator.simulate(scan->poses[k], mix_seed(seed, k)).raw);
                }
                hook("fuse", 0.0);
                auto fused = std::make_shared<PointCloud>(scanner::fuse_scans(raws, fuse));
                hook("done", 1.0);
                return fused;
            });
            truth->cloud = scan->cloud;
            scan->truth = truth;
            return scan;
        },
        py::arg("scene") = "ibeam-channel", py::arg("poses") = 3, py::arg("seed") = 1,
        py::kw_only(), py::arg("readings") = 5, py::arg("trim") = 1,
        py::arg("laser") = "urg04lx-paper", py::arg("noise") = "datasheet",
        py::arg("optical_offset") = 0.040, py::arg("min_range") = py::none(),
        py::arg("max_range") = py::none(), py::arg("veil_angle") = 0.0,
        py::arg("progress") = py::none(),
        "Simulates a tilting URG-04LX scanning a scene from several poses and fuses the scans, "
        "as `surfgrow scan` does (same arguments, same points). scene: a built-in name "
        "('ibeam-channel', 'room-corner', 'pipes', 'corridor', 'stairs') or a scene file. poses: "
        "a count along the scene's scan path, or a poses file. Lengths in metres. veil_angle: "
        "drop mixed pixels when fusing, as `--veil-angle` (degrees, e.g. 10; 0 keeps every ray).");

    m.def(
        "evaluate",
        [](std::shared_ptr<const Grown> grown, std::shared_ptr<const Truth> truth, double workspace,
           double band) {
            if (truth->cloud->size() != grown->cloud->view().size())
                invalid(cat({"the truth is of ", std::to_string(truth->cloud->size()),
                             " points but the result was grown from ",
                             std::to_string(grown->cloud->view().size())}));
            eval::EvalOptions o;
            o.workspace_m = workspace;
            o.band_m = band;
            eval::EvalReport report;
            {
                py::gil_scoped_release release;
                report = eval::evaluate(*truth->cloud, grown->result, truth->scene->faces(), o);
            }
            return to_python(eval::to_json(report));
        },
        py::arg("result"), py::arg("truth"), py::kw_only(), py::arg("workspace") = 1.0,
        py::arg("band") = 0.5,
        "Scores a GrowResult against a simulated scan's Truth (docs/evaluation.md): registered "
        "shares, per-point normal errors (median, p95, share over 45 degrees), purity, faces, "
        "by range band. Returns eval.json's content as a dict.");
}

}  // namespace surfgrow::python
