// surfgrow.bound_planes, coverage, occupancy and CollisionSpheres: the robot's outputs.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "grown.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/octomap_export.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/collision_spheres.hpp"
#include "surfgrow/robot/coverage.hpp"
#include "surfgrow/robot/occupancy_grid.hpp"
#include "surfgrow/robot/sensor_origins.hpp"

namespace surfgrow::python {

namespace {

struct Planes {
    std::shared_ptr<const Grown> grown;
    SharedCloud cloud;
    BoundPlanes planes;
};

struct Coverage {
    std::shared_ptr<const Planes> planes;
    CoveragePlan plan;
};

struct Occupancy {
    SharedCloud cloud;
    OccupancyGrid grid;
    SensorOrigins origins;
    int threads = 0;  // the GrowResult's
};

struct Collision {
    CollisionSpheres env;
    Vec3d offset = Vec3d::Zero();  // spheres are stored relative to it, queries come absolute
};

py::array_t<double> ring_world(const BoundPlane& p, const Ring& ring, const Vec3d& offset) {
    return rows3(ring.size(), [&](std::size_t i) { return Vec3d(p.to_world(ring[i]) + offset); });
}

py::dict face_dict(const BoundPlane& p, const Vec3d& offset) {
    py::dict d;
    const Vec3d c = p.centroid + offset;
    d["normal"] = vec3_array(p.normal);
    d["centroid"] = vec3_array(c);
    py::array_t<double> plane(4);
    for (py::ssize_t k = 0; k < 3; ++k) plane.mutable_data()[k] = p.normal[k];
    plane.mutable_data()[3] = -p.normal.dot(c);
    d["plane"] = plane;
    d["u_axis"] = vec3_array(p.u_axis);
    d["v_axis"] = vec3_array(p.v_axis);
    d["area"] = p.area;
    d["rms"] = p.rms;
    d["point_count"] = p.point_count;
    d["degenerate"] = p.degenerate;
    d["members"] =
        column<std::uint32_t>(p.patches.size(), [&](std::size_t i) { return p.patches[i]; });
    py::list polygons;
    for (const PolygonWithHoles& poly : p.polygons) {
        py::list holes;
        for (const Ring& h : poly.holes) holes.append(ring_world(p, h, offset));
        py::dict q;
        q["outer"] = ring_world(p, poly.outer, offset);
        q["holes"] = holes;
        polygons.append(q);
    }
    d["polygons"] = polygons;
    return d;
}

// Query shapes from an array: (M, 3) points, (M, 4) spheres (x, y, z, r), (M, 7) capsules
// (ax, ay, az, bx, by, bz, r); one row may be given as a 1-D array.
std::vector<Capsule> queries_from(const py::handle& q, const Vec3d& offset) {
    py::array a = py::array::ensure(q);
    if (!a) invalid("queries must be an array of numbers");
    const py::ssize_t cols = a.ndim() == 1 ? a.shape(0) : a.ndim() == 2 ? a.shape(1) : 0;
    if (cols != 3 && cols != 4 && cols != 7)
        invalid(
            "queries must have shape (M, 3) points, (M, 4) spheres x y z r, or (M, 7) "
            "capsules ax ay az bx by bz r");
    const auto d = doubles_2d(a, "queries", cols);
    const auto r = d.unchecked<2>();
    std::vector<Capsule> out(static_cast<std::size_t>(d.shape(0)));
    for (std::size_t i = 0; i < out.size(); ++i) {
        const auto row = static_cast<py::ssize_t>(i);
        Capsule& c = out[i];
        c.a = Vec3d(r(row, 0), r(row, 1), r(row, 2)) - offset;
        c.b = cols == 7 ? Vec3d(Vec3d(r(row, 3), r(row, 4), r(row, 5)) - offset) : c.a;
        c.radius = cols == 3 ? 0.0 : r(row, cols - 1);
        if (c.radius < 0)
            invalid(cat({"queries row ", std::to_string(i), " has a negative radius"}));
    }
    return out;
}

}  // namespace

void bind_robot(py::module_& m) {
    // --- Bound planes.
    py::class_<Planes, std::shared_ptr<Planes>>(
        m, "BoundPlanes",
        "Structural faces: neighbouring coplanar surfaces merged, each with its plane, member "
        "surfaces and points, area and boundary polygons. Ordered by point count.")
        .def("__len__", [](const Planes& p) { return p.planes.planes.size(); })
        .def_property_readonly(
            "faces",
            [](const Planes& p) {
                py::list faces;
                for (const BoundPlane& b : p.planes.planes)
                    faces.append(face_dict(b, p.cloud->view().offset));
                return faces;
            },
            "list of dicts: plane (a, b, c, d), normal, centroid, u_axis, v_axis, area, rms, "
            "point_count, degenerate, members (surface ids), polygons ([{'outer': (K, 3), "
            "'holes': [(K, 3), ...]}], world coordinates)")
        .def_property_readonly(
            "normals",
            [](const Planes& p) {
                return rows3(p.planes.planes.size(),
                             [&](std::size_t i) { return p.planes.planes[i].normal; });
            },
            "(P, 3) float64 unit normals")
        .def_property_readonly(
            "planes",
            [](const Planes& p) {
                const auto& b = p.planes.planes;
                return plane_rows(b.size(), [&](std::size_t i) {
                    return std::pair{b[i].normal, Vec3d(b[i].centroid + p.cloud->view().offset)};
                });
            },
            "(P, 4) float64 planes (a, b, c, d): n . x + d = 0")
        .def_property_readonly(
            "areas",
            [](const Planes& p) {
                return column<double>(p.planes.planes.size(),
                                      [&](std::size_t i) { return p.planes.planes[i].area; });
            },
            "(P,) float64 areas [units^2]")
        .def_property_readonly(
            "plane_of_surface",
            [](py::object self) {
                const auto& p = self.cast<const Planes&>();
                return view(p.planes.plane_of_patch.data(),
                            {static_cast<py::ssize_t>(p.planes.plane_of_patch.size())}, self);
            },
            "(S,) int32: the face of every surface, or -1")
        .def_property_readonly(
            "point_labels",
            [](const Planes& p) {
                const std::vector<std::int32_t> l = plane_labels(p.planes, p.grown->result.labels);
                return column<std::int32_t>(l.size(), [&](std::size_t i) { return l[i]; });
            },
            "(N,) int32: the face of every input point, or -1")
        .def_property_readonly("stats", [](const Planes& p) {
            const BoundPlaneStats& s = p.planes.stats;
            py::dict d;
            d["patches"] = s.patches;
            d["patches_merged"] = s.patches_merged;
            d["adjacent_pairs"] = s.adjacent_pairs;
            d["points"] = s.points;
            d["degenerate"] = s.degenerate;
            d["area"] = s.area;
            d["noise"] = s.noise;
            return d;
        });

    m.def(
        "bound_planes",
        [](std::shared_ptr<const Grown> grown, const py::object& points, double max_angle_deg,
           double max_offset, double adjacency, double max_gap, double resolution,
           double closing_radius, double simplify_tolerance) {
            auto p = std::make_shared<Planes>();
            p->grown = grown;
            p->cloud = cloud_for(*grown, points);
            BoundPlaneConfig c;
            c.mu = grown->config.mu;
            c.threads = grown->config.threads;
            c.max_angle_deg = max_angle_deg;
            c.max_offset = max_offset;
            c.adjacency = adjacency;
            c.max_gap = max_gap;
            c.resolution = resolution;
            c.closing_radius = closing_radius;
            c.simplify_tolerance = simplify_tolerance;
            validate(c);
            py::gil_scoped_release release;
            p->planes = compute_bound_planes(p->cloud->view(), grown->result, c);
            return p;
        },
        py::arg("result"), py::arg("points") = py::none(), py::kw_only(),
        py::arg("max_angle_deg") = 10.0, py::arg("max_offset") = 0.0, py::arg("adjacency") = 0.0,
        py::arg("max_gap") = 0.0, py::arg("resolution") = 0.0, py::arg("closing_radius") = 0.0,
        py::arg("simplify_tolerance") = 0.0,
        "Merges a GrowResult's surfaces into bound planes. `points`: the cloud it was grown from "
        "(optional: the result keeps it). Lengths of 0 take their defaults from mu.");

    // --- Coverage.
    py::class_<Coverage, std::shared_ptr<Coverage>>(
        m, "CoveragePlan",
        "Coverage goals on the bound planes in path order, each with the tool's approach pose.")
        .def("__len__", [](const Coverage& c) { return c.plan.goals.size(); })
        .def_property_readonly(
            "positions",
            [](const Coverage& c) {
                const Vec3d o = c.planes->cloud->view().offset;
                return rows3(c.plan.goals.size(),
                             [&](std::size_t i) { return Vec3d(c.plan.goals[i].position + o); });
            },
            "(G, 3) float64 goal points on the surfaces, in path order")
        .def_property_readonly(
            "normals",
            [](const Coverage& c) {
                return rows3(c.plan.goals.size(),
                             [&](std::size_t i) { return c.plan.goals[i].normal; });
            },
            "(G, 3) float64: the plane's normal at each goal")
        .def_property_readonly(
            "tool_positions",
            [](const Coverage& c) {
                const Vec3d o = c.planes->cloud->view().offset;
                return rows3(c.plan.goals.size(), [&](std::size_t i) {
                    return Vec3d(c.plan.goals[i].tool_position + o);
                });
            },
            "(G, 3) float64: where the tool is, standoff back along its axis (the tool path)")
        .def_property_readonly(
            "tool_axes",
            [](const Coverage& c) {
                return rows3(c.plan.goals.size(),
                             [&](std::size_t i) { return c.plan.goals[i].tool_axis; });
            },
            "(G, 3) float64 unit axes from the tool towards the goal (the jet)")
        .def_property_readonly(
            "orientations",
            [](const Coverage& c) {
                const auto& g = c.plan.goals;
                py::array_t<double> a({static_cast<py::ssize_t>(g.size()), py::ssize_t{4}});
                auto w = a.mutable_unchecked<2>();
                for (std::size_t i = 0; i < g.size(); ++i) {
                    const auto r = static_cast<py::ssize_t>(i);
                    const Eigen::Quaterniond& q = g[i].orientation;
                    w(r, 0) = q.x();
                    w(r, 1) = q.y();
                    w(r, 2) = q.z();
                    w(r, 3) = q.w();
                }
                return a;
            },
            "(G, 4) float64 tool frame quaternions (x, y, z, w) as ROS writes them: z the tool "
            "axis, x the sweep direction")
        .def_property_readonly(
            "tilt_deg",
            [](const Coverage& c) {
                return column<double>(c.plan.goals.size(),
                                      [&](std::size_t i) { return c.plan.goals[i].tilt_deg; });
            },
            "(G,) float64: angle between the jet and the normal")
        .def_property_readonly(
            "planes",
            [](const Coverage& c) {
                return column<std::uint32_t>(c.plan.goals.size(),
                                             [&](std::size_t i) { return c.plan.goals[i].plane; });
            },
            "(G,) uint32: the bound plane of each goal")
        .def_property_readonly(
            "transitions",
            [](const Coverage& c) {
                return column<bool>(c.plan.goals.size(),
                                    [&](std::size_t i) { return c.plan.goals[i].transition; });
            },
            "(G,) bool: the first goal of a plane reached from another plane")
        .def_property_readonly("stats", [](const Coverage& c) {
            const CoverageStats& s = c.plan.stats;
            py::dict d;
            d["goals"] = s.goals;
            d["planes"] = s.planes;
            d["transitions"] = s.transitions;
            d["area"] = s.area;
            d["covered_area"] = s.covered_area;
            d["coverage"] = s.coverage;
            d["tool_path_length"] = s.tool_path_length;
            d["sweep_length"] = s.sweep_length;
            d["transition_length"] = s.transition_length;
            d["goal_path_length"] = s.goal_path_length;
            return d;
        });

    m.def(
        "coverage",
        [](std::shared_ptr<const Planes> planes, double blast_radius, double standoff,
           double min_angle_deg, double max_angle_deg, std::optional<double> tilt_deg,
           double sample_spacing, const py::object& start) {
            auto c = std::make_shared<Coverage>();
            c->planes = planes;
            CoverageConfig cfg;
            cfg.blast_radius = blast_radius;
            cfg.standoff = standoff;
            cfg.min_angle_deg = min_angle_deg;
            cfg.max_angle_deg = max_angle_deg;
            cfg.tilt_deg = tilt_deg;
            cfg.sample_spacing = sample_spacing;
            if (auto s = optional_vec3(start, "start"))
                cfg.start = *s - planes->cloud->view().offset;
            cfg.threads = planes->grown->config.threads;
            validate(cfg);
            py::gil_scoped_release release;
            c->plan = plan_coverage(planes->planes, planes->grown->result, cfg);
            return c;
        },
        py::arg("planes"), py::arg("blast_radius") = 0.0, py::arg("standoff") = 0.3, py::kw_only(),
        py::arg("min_angle_deg") = 5.0, py::arg("max_angle_deg") = 40.0,
        py::arg("tilt_deg") = py::none(), py::arg("sample_spacing") = 0.0,
        py::arg("start") = py::none(),
        "Plans goals whose blast discs (radius blast_radius; 0: mu) cover every bound plane, a "
        "path through them, and the tool's pose at standoff, tilted min_angle_deg..max_angle_deg "
        "from the normal (paper 5.5).");

    // --- Occupancy.
    py::class_<Occupancy, std::shared_ptr<Occupancy>>(
        m, "OccupancyGrid",
        "The cubes of side mu that hold registered points, on the grower's own grid.")
        .def("__len__", [](const Occupancy& o) { return o.grid.size(); })
        .def_property_readonly(
            "cells",
            [](const Occupancy& o) {
                const auto cells = o.grid.cells();
                py::array_t<std::int32_t> a(
                    {static_cast<py::ssize_t>(cells.size()), py::ssize_t{3}});
                auto w = a.mutable_unchecked<2>();
                for (std::size_t i = 0; i < cells.size(); ++i)
                    for (py::ssize_t k = 0; k < 3; ++k)
                        w(static_cast<py::ssize_t>(i), k) = cells[i][k];
                return a;
            },
            "(K, 3) int32 integer cube coordinates, sorted by x, y, z")
        .def_property_readonly(
            "centres",
            [](const Occupancy& o) {
                const auto cells = o.grid.cells();
                return rows3(cells.size(), [&](std::size_t i) {
                    return Vec3d(o.grid.centre(cells[i]) + o.cloud->view().offset);
                });
            },
            "(K, 3) float64 cube centres")
        .def_property_readonly(
            "point_counts",
            [](const Occupancy& o) {
                const auto counts = o.grid.point_counts();
                return column<std::uint32_t>(counts.size(),
                                             [&](std::size_t i) { return counts[i]; });
            },
            "(K,) uint32 registered points per cube")
        .def_property_readonly(
            "cube_size", [](const Occupancy& o) { return o.grid.cube_size(); },
            "the side: mu (1 + 2^-20)")
        .def_property_readonly(
            "origin",
            [](const Occupancy& o) {
                return vec3_array(Vec3d(o.grid.origin() + o.cloud->view().offset));
            },
            "(3,) low corner of cube (0, 0, 0)")
        .def(
            "occupied",
            [](const Occupancy& o, const py::object& points) {
                const auto d = doubles_2d(points, "points", 3);
                const auto r = d.unchecked<2>();
                const Vec3d off = o.cloud->view().offset;
                return column<bool>(static_cast<std::size_t>(d.shape(0)), [&](std::size_t i) {
                    const auto row = static_cast<py::ssize_t>(i);
                    return o.grid.occupied(Vec3d(r(row, 0), r(row, 1), r(row, 2)) - off);
                });
            },
            py::arg("points"), "(M,) bool: whether each point's cube is occupied")
        .def(
            "write_octomap",
            [](const Occupancy& o, const std::filesystem::path& path) {
                io::OctomapSummary s;
                {
                    py::gil_scoped_release release;
                    io::write_atomically(path, [&](std::ostream& out) {
                        s = io::write_octomap_bt(out, o.grid, o.cloud->view(), {}, o.origins,
                                                 o.threads);
                    });
                }
                py::dict d;
                d["resolution"] = s.resolution;
                d["occupied"] = s.occupied;
                d["free"] = s.free;
                d["rays"] = s.rays;
                d["carving"] = sensor_origins_name(s.carving);
                return d;
            },
            py::arg("path"),
            "Writes the grid as an OctoMap .bt (atomically), free space carved by rays from the "
            "sensor origins when known. Returns counts of occupied and free leaves.");

    m.def(
        "occupancy",
        [](std::shared_ptr<const Grown> grown, const py::object& points,
           const py::object& origins) {
            auto o = std::make_shared<Occupancy>();
            SharedCloud cloud = cloud_for(*grown, points);
            if (!origins.is_none()) {
                std::vector<Vec3d> rows = rows3_from(origins, "origins");
                for (Vec3d& r : rows) r -= cloud->view().offset;
                cloud = HeldCloud::with_origins(std::move(cloud), std::move(rows));
            }
            o->cloud = cloud;
            GrowerConfig cfg = grown->config;
            if (!origins.is_none()) cfg.viewpoint.reset();
            o->origins = sensor_origins(cloud->view(), cfg);
            o->threads = cfg.threads;
            py::gil_scoped_release release;
            o->grid = occupancy_grid(cloud->view(), grown->result, cfg);
            return o;
        },
        py::arg("result"), py::arg("points") = py::none(), py::kw_only(),
        py::arg("origins") = py::none(),
        "The occupancy grid of a GrowResult. origins: where the scans were taken from, for "
        "carving free space in write_octomap: one (3,) origin for every point, or (K, 3) for a "
        "fused Cloud's K scans; default: the cloud's own (scan origins or viewpoint).");

    // --- Collision spheres.
    py::class_<Collision, std::shared_ptr<Collision>>(
        m, "CollisionSpheres",
        "The environment as spheres (paper 5.5: one per surface at its home point, radius mu), "
        "with vectorised proximity queries. Queries run in parallel without the GIL.")
        .def(py::init([](std::shared_ptr<const Grown> grown) {
                 auto c = std::make_shared<Collision>();
                 c->env = CollisionSpheres::from_surfaces(grown->result.surfaces);
                 c->offset = grown->cloud->view().offset;
                 return c;
             }),
             py::arg("result"), "One sphere per surface of a GrowResult (sphere id = surface id).")
        .def(py::init([](const py::object& centres, const py::object& radii) {
                 const std::vector<Vec3d> at = rows3_from(centres, "centres");
                 const auto r = py::array_t<double, py::array::forcecast>::ensure(radii);
                 if (!r || (r.size() != 1 && r.size() != static_cast<py::ssize_t>(at.size())))
                     invalid("radii must be one number or one per centre");
                 std::vector<Sphere> s(at.size());
                 for (std::size_t i = 0; i < s.size(); ++i)
                     s[i] = {at[i], r.data()[r.size() == 1 ? 0 : i]};
                 auto c = std::make_shared<Collision>();
                 c->env = CollisionSpheres(std::move(s));
                 return c;
             }),
             py::arg("centres"), py::arg("radii"), "Spheres from (M, 3) centres and radii.")
        .def("__len__", [](const Collision& c) { return c.env.size(); })
        .def(
            "nearest",
            [](const Collision& c, const py::object& queries) {
                const std::vector<Capsule> q = queries_from(queries, c.offset);
                py::array_t<double> clearance(static_cast<py::ssize_t>(q.size()));
                py::array_t<std::int64_t> ids(static_cast<py::ssize_t>(q.size()));
                double* cl = clearance.mutable_data();
                std::int64_t* id = ids.mutable_data();
                {
                    py::gil_scoped_release release;
                    const auto n = static_cast<std::int64_t>(q.size());
#pragma omp parallel for num_threads(resolve_threads(0)) schedule(static, 256)
                    for (std::int64_t i = 0; i < n; ++i) {
                        const Proximity p = c.env.nearest(q[static_cast<std::size_t>(i)]);
                        cl[i] = p.clearance;
                        id[i] = p.nearest;
                    }
                }
                return py::make_tuple(clearance, ids);
            },
            py::arg("queries"),
            "(clearance, ids) for (M, 3) points, (M, 4) spheres (x, y, z, r) or (M, 7) capsules "
            "(ax, ay, az, bx, by, bz, r): the signed distance to the nearest sphere (negative: "
            "penetrating; inf when empty) and its id (-1 when empty).")
        .def(
            "collides",
            [](const Collision& c, const py::object& queries, double tolerance) {
                if (!std::isfinite(tolerance)) invalid("tolerance must be finite");
                const std::vector<Capsule> q = queries_from(queries, c.offset);
                py::array_t<bool> out(static_cast<py::ssize_t>(q.size()));
                bool* hit = out.mutable_data();
                {
                    py::gil_scoped_release release;
                    const auto n = static_cast<std::int64_t>(q.size());
#pragma omp parallel for num_threads(resolve_threads(0)) schedule(static, 256)
                    for (std::int64_t i = 0; i < n; ++i)
                        hit[i] = c.env.collides(q[static_cast<std::size_t>(i)], tolerance);
                }
                return out;
            },
            py::arg("queries"), py::arg("tolerance") = 0.0,
            "(M,) bool: whether any sphere is closer than `tolerance` to each query shape.");
}

}  // namespace surfgrow::python
