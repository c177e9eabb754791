// CGAL 5.5 (Debian libcgal-dev) in the peers' harness.
//
//   peer_cgal CLOUD --method region-growing|ransac --out DIR [--k 20] [--mu 0.012]
//             [--tol 0.012] [--angle 15] [--min-pts 10] [--min-plane 0] [--threads 2]
//             [--probability 0.05] [--min-seconds 1] [--max-repeats 5]
//
// I/O = CGAL::IO::read_points (PLY) into (point, normal) pairs. Algorithm, both methods:
// pca_estimate_normals (k nearest, Parallel_if_available_tag: TBB threads), then
//   region-growing: Shape_detection::Region_growing on the point set with K_neighbor_query (k),
//     Least_squares_plane_fit_region (max distance tol, max angle, min region size min-pts) and
//     Least_squares_plane_fit_sorting seeds (CGAL's recommended order); PCA plane per region.
//   ransac: Efficient_RANSAC with planes only. CGAL assigns the final points of a shape within
//     3 epsilon (Efficient_RANSAC.h, the score call with FT(3) * epsilon; CGAL issue #6186), so
//     epsilon = tol / 3 makes the assignment tolerance tol like every other tool's;
//     cluster_epsilon = mu (points within mu are connected), normal_threshold = cos(angle),
//     min_points = --min-plane (0: max(min-pts, N/1000)), probability 0.05 (CGAL's own example).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/Shape_detection/Efficient_RANSAC.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing_on_point_set.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <tuple>

#include "peer_common.hpp"
#include "segment_planes.hpp"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
// Point, normal and input index: Efficient_RANSAC reorders its input range in place, so each
// point carries its index in the file.
using PN = std::tuple<Point, Vector, std::size_t>;
using PNs = std::vector<PN>;
using PointMap = CGAL::Nth_of_tuple_property_map<0, PN>;
using NormalMap = CGAL::Nth_of_tuple_property_map<1, PN>;

namespace SD = CGAL::Shape_detection;

struct Output {
    std::vector<std::int32_t> labels;
    std::vector<double> planes;
    std::map<std::string, double> stages;
};

void estimate_normals(PNs& pns, int k, Output& o) {
    const double t = peers::now_s();
    CGAL::pca_estimate_normals<CGAL::Parallel_if_available_tag>(
        pns, static_cast<unsigned>(k),
        CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()));
    o.stages["normals"] = peers::now_s() - t;
}

Output region_growing(PNs& pns, const peers::Args& a) {
    using Query = SD::Point_set::K_neighbor_query<Kernel, PNs, PointMap>;
    using Region = SD::Point_set::Least_squares_plane_fit_region<Kernel, PNs, PointMap, NormalMap>;
    using Sorting = SD::Point_set::Least_squares_plane_fit_sorting<Kernel, PNs, Query, PointMap>;
    using Growing = SD::Region_growing<PNs, Query, Region, typename Sorting::Seed_map>;
    Output o;
    const int k = a.integer("k", 20);
    estimate_normals(pns, k, o);

    double t = peers::now_s();
    Query query(pns, static_cast<std::size_t>(k));
    Region region(pns, a.num("tol", 0.012), a.num("angle", 15.0),
                  static_cast<std::size_t>(a.integer("min-pts", 10)));
    Sorting sorting(pns, query);
    sorting.sort();
    o.stages["kdtree_and_seed_order"] = peers::now_s() - t;

    t = peers::now_s();
    Growing growing(pns, query, region, sorting.seed_map());
    std::vector<std::vector<std::size_t>> regions;
    growing.detect(std::back_inserter(regions));
    o.stages["region_growing"] = peers::now_s() - t;

    t = peers::now_s();
    o.labels.assign(pns.size(), -1);
    for (std::size_t r = 0; r < regions.size(); ++r) {
        for (const std::size_t i : regions[r]) o.labels[i] = static_cast<std::int32_t>(r);
    }
    o.planes = peers::fit_segment_planes(o.labels, regions.size(), [&](std::size_t i) {
        const Point& p = std::get<0>(pns[i]);
        return Eigen::Vector3d(p.x(), p.y(), p.z());
    });
    o.stages["planes"] = peers::now_s() - t;
    return o;
}

Output ransac(PNs& pns, const peers::Args& a) {
    using Traits = SD::Efficient_RANSAC_traits<Kernel, PNs, PointMap, NormalMap>;
    using Ransac = SD::Efficient_RANSAC<Traits>;
    using Plane = SD::Plane<Traits>;
    Output o;
    estimate_normals(pns, a.integer("k", 20), o);

    const double t = peers::now_s();
    Ransac ransac;
    ransac.set_input(pns);
    ransac.add_shape_factory<Plane>();
    Ransac::Parameters prm;
    const std::size_t min_pts = static_cast<std::size_t>(a.integer("min-pts", 10));
    std::size_t min_plane = static_cast<std::size_t>(a.integer("min-plane", 0));
    if (min_plane == 0) min_plane = std::max(min_pts, pns.size() / 1000);
    prm.probability = a.num("probability", 0.05);
    prm.min_points = min_plane;
    prm.epsilon = a.num("tol", 0.012) / 3.0;
    prm.cluster_epsilon = a.num("mu", 0.012);
    prm.normal_threshold = std::cos(a.num("angle", 15.0) * std::numbers::pi / 180.0);
    ransac.detect(prm);
    o.stages["ransac"] = peers::now_s() - t;

    o.labels.assign(pns.size(), -1);
    std::int32_t id = 0;
    for (const auto& shape : ransac.shapes()) {
        const auto* plane = dynamic_cast<const Plane*>(shape.get());
        if (plane == nullptr) continue;
        const Kernel::Plane_3 pl = static_cast<Kernel::Plane_3>(*plane);
        const double len = std::sqrt(pl.a() * pl.a() + pl.b() * pl.b() + pl.c() * pl.c());
        o.planes.insert(o.planes.end(), {pl.a() / len, pl.b() / len, pl.c() / len, pl.d() / len});
        for (const std::size_t i : shape->indices_of_assigned_points())
            o.labels[std::get<2>(pns[i])] = id;
        ++id;
    }
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const peers::Args args(argc, argv);
        const std::string out = args.str("out", ".");
        peers::Report rep;
        rep.tool = "cgal";
        rep.method = args.str("method", "region-growing");
        rep.input = args.input();
        rep.threads = args.integer("threads", 2);
#ifdef CGAL_LINKED_WITH_TBB
        const tbb::global_control tbb_threads(tbb::global_control::max_allowed_parallelism,
                                              static_cast<std::size_t>(rep.threads));
        rep.notes["tbb"] = "yes";
#else
        rep.notes["tbb"] = "no (normals on one thread)";
#endif
        rep.baseline_rss = peers::proc_status_bytes("VmRSS");

        const double t0 = peers::now_s();
        std::vector<Point> points;
        if (!CGAL::IO::read_points(rep.input, std::back_inserter(points)))
            throw std::runtime_error("cannot read " + rep.input);
        PNs input;
        input.reserve(points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
            input.emplace_back(points[i], CGAL::NULL_VECTOR, i);
        points = {};
        rep.io_seconds = peers::now_s() - t0;
        rep.points = input.size();
        rep.input_rss = peers::proc_status_bytes("VmRSS");

        for (const char* key : {"k", "mu", "tol", "angle", "min-pts", "min-plane", "probability"}) {
            if (args.has(key)) rep.params[key] = args.num(key, 0);
        }
        Output result;
        rep.algorithm_peak_valid = peers::reset_peak_rss();
        rep.algorithm_seconds = peers::repeat_timed(
            [&](int run) {
                PNs pns = input;  // normals are written in place: start clean each run
                Output o = rep.method == "ransac" ? ransac(pns, args) : region_growing(pns, args);
                if (run == 0) {
                    result = std::move(o);
                    rep.algorithm_peak_rss = peers::proc_status_bytes("VmHWM");
                }
            },
            args.num("min-seconds", 1.0), args.integer("max-repeats", 5),
            rep.algorithm_cpu_seconds);
        rep.stage_seconds = result.stages;
        rep.segments = result.planes.size() / 4;
        peers::write_binary(out + "/labels.i32", result.labels);
        peers::write_binary(out + "/planes.f64", result.planes);
        peers::write_report(out + "/result.json", rep);
        std::cout << "cgal " << rep.method << ": " << rep.points << " points -> " << rep.segments
                  << " segments in " << peers::median(rep.algorithm_seconds) << " s\n";
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "peer_cgal: " << e.what() << "\n";
        return 1;
    }
}
