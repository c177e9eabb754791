// surfgrow in the peers' harness: the library called as the README shows, timed like the peers.
//
//   peer_surfgrow CLOUD --out DIR [--mu 0.012] [--min-pts 10] [--threads 0] [--seed 1]
//                 [--mu-max 0] [--paper] [--planes] [--min-seconds 1] [--max-repeats 5]
//
// I/O = io::read_cloud. Algorithm = grow_surfaces (cube index, growing, leftover pass, normal
// pooling, statistics), everything else at its default, as `surfgrow grow` runs it.
// --paper: the paper's plane test, eq. (2) alone, with the adaptive radius up to 2 mu and normal
// pooling over 2 mu (surfgrow's defaults before the disk test).
// --planes: also compute_bound_planes (planes.json's planes: patches merged into faces, a plane
// fitted to each face's points, boundary polygons), timed with the growing; the segments are then
// the bound planes, like the peers' planes.
#include <cstring>
#include <iostream>

#include "peer_common.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/planes/bound_planes.hpp"

int main(int argc, char** argv) {
    try {
        const peers::Args args(argc, argv);
        const std::string out = args.str("out", ".");
        peers::Report rep;
        rep.tool = "surfgrow";
        const bool bound = args.has("planes");
        const bool paper = args.has("paper");
        rep.method = bound ? "planes" : paper ? "grow-paper" : "grow";
        rep.input = args.input();
        rep.baseline_rss = peers::proc_status_bytes("VmRSS");

        const double t0 = peers::now_s();
        surfgrow::io::ReadOptions ro;
        ro.read_labels = false;  // the truth labels are the driver's business
        const surfgrow::PointCloud cloud = surfgrow::io::read_cloud(rep.input, ro);
        rep.io_seconds = peers::now_s() - t0;
        rep.points = cloud.size();
        rep.input_rss = peers::proc_status_bytes("VmRSS");

        surfgrow::GrowerConfig cfg;
        cfg.mu = args.num("mu", 0.012);
        cfg.min_pts = args.integer("min-pts", 10);
        cfg.threads = args.integer("threads", 0);
        cfg.seed = static_cast<std::uint64_t>(args.num("seed", 1));
        // --mu-max: the adaptive radius's ceiling; absent, the library's default (8 mu).
        if (paper) {
            cfg.plane_test = surfgrow::PlaneTest::kPaper;
            cfg.adaptive_factor = 2.0;
            cfg.pool_radius = 2 * cfg.mu;
        }
        if (const double mu_max = args.num("mu-max", 0.0); mu_max > 0)
            cfg.adaptive_factor = mu_max / cfg.mu;
        rep.threads = cfg.threads;
        rep.params = {{"mu", cfg.mu},
                      {"min_pts", cfg.min_pts},
                      {"alpha", cfg.alpha},
                      {"plane_tolerance", cfg.tolerance()},
                      {"pool_angle_deg", cfg.pool_angle_deg},
                      {"mu_max", cfg.max_radius()},
                      {"seed", static_cast<double>(cfg.seed)}};

        surfgrow::BoundPlaneConfig bpc;  // every bound-plane option at its default
        bpc.mu = cfg.mu;
        bpc.threads = cfg.threads;
        surfgrow::GrowResult result;
        surfgrow::BoundPlanes bound_planes;
        double bound_seconds = 0;
        rep.algorithm_peak_valid = peers::reset_peak_rss();
        rep.algorithm_seconds = peers::repeat_timed(
            [&](int run) {
                surfgrow::GrowResult r = surfgrow::grow_surfaces(cloud, cfg);
                surfgrow::BoundPlanes b;
                const double tb = peers::now_s();
                if (bound) b = surfgrow::compute_bound_planes(cloud, r, bpc);
                if (run == 0) {
                    bound_seconds = peers::now_s() - tb;
                    result = std::move(r);
                    bound_planes = std::move(b);
                    // Peak of the first run, before a repeat's second result coexists with it.
                    rep.algorithm_peak_rss = peers::proc_status_bytes("VmHWM");
                }
            },
            args.num("min-seconds", 1.0), args.integer("max-repeats", 5),
            rep.algorithm_cpu_seconds);
        rep.stage_seconds = {{"index", result.stats.seconds.index},
                             {"grow", result.stats.seconds.grow},
                             {"attach", result.stats.seconds.attach},
                             {"finish", result.stats.seconds.finish}};
        if (bound) rep.stage_seconds["bound_planes"] = bound_seconds;
        rep.segments = result.surfaces.size();
        rep.notes["registered_reported"] = std::to_string(result.stats.registered);
        rep.notes["outputs_bytes"] =
            std::to_string(result.labels.size() * sizeof(std::int32_t) +
                           result.surfaces.size() * sizeof(surfgrow::Surface));

        std::vector<double> planes;
        if (bound) {
            rep.segments = bound_planes.planes.size();
            for (const surfgrow::BoundPlane& b : bound_planes.planes) {
                const surfgrow::Plane pl = b.plane();
                planes.insert(planes.end(), {pl.normal.x(), pl.normal.y(), pl.normal.z(), pl.d});
            }
            peers::write_binary(out + "/labels.i32",
                                surfgrow::plane_labels(bound_planes, result.labels));
        } else {
            planes.reserve(4 * result.surfaces.size());
            for (const surfgrow::Surface& s : result.surfaces) {
                planes.insert(planes.end(),
                              {s.normal.x(), s.normal.y(), s.normal.z(), s.plane_offset()});
            }
            peers::write_binary(out + "/labels.i32", result.labels);
        }
        peers::write_binary(out + "/planes.f64", planes);
        peers::write_report(out + "/result.json", rep);
        std::cout << "surfgrow: " << rep.points << " points -> " << rep.segments
                  << (bound ? " planes in " : " surfaces in ")
                  << peers::median(rep.algorithm_seconds) << " s\n";
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "peer_surfgrow: " << e.what() << "\n";
        return 1;
    }
}
