// The study behind docs/planes-and-coverage.md: bound planes and coverage on the built-in
// scenes, scored against their ground truth, for a few merge angles and offsets.
// Run: build/bench/planes_study [scene ...]
#include <cstdio>
#include <string>
#include <vector>

#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/eval/segmentation_score.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/coverage.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

using namespace surfgrow;

namespace {

void study(const std::string& name) {
    const scanner::SceneDescription desc = scanner::builtin_scene(name);
    const scanner::Scene scene(desc);
    std::vector<scanner::RawScan> raws;
    for (scanner::SimulatedScan& s :
         scanner::ScanSimulator(scene).simulate(scanner::scan_poses(desc.scanner, 3), 1))
        raws.push_back(std::move(s.raw));
    PointCloud cloud = scanner::fuse_scans(raws);
    // Only planar faces are scored: a cylinder's side is cut into strips by design.
    for (std::int32_t& l : cloud.labels)
        if (l >= 0 && !scene.faces()[static_cast<std::size_t>(l)].planar()) l = -1;
    const GrowResult grown = grow_surfaces(cloud, GrowerConfig{});
    const std::vector<std::int32_t> pieces = eval::truth_pieces(cloud.points, cloud.labels, 0.024);
    std::printf("\n%s: %zu points, %zu surfaces, %.1f%% registered\n", name.c_str(), cloud.size(),
                grown.surfaces.size(), 100 * grown.stats.registered_fraction());
    std::printf(
        "%6s %6s %5s | %6s %6s | faces over under one | pieces over under one | best%% | s\n",
        "angle", "offset", "gap", "planes", "noise");
    struct Variant {
        double angle, offset_mm, gap_mm;
    };
    for (const Variant v :
         {Variant{10, 0, 0}, Variant{5, 0, 0}, Variant{15, 0, 0}, Variant{10, 3, 0},
          Variant{10, 8, 0}, Variant{10, 12, 0}, Variant{10, 0, -1}, Variant{10, 0, 120}}) {
        {
            const double angle = v.angle;
            BoundPlaneConfig cfg;
            cfg.max_angle_deg = v.angle;
            cfg.max_offset = v.offset_mm / 1000;
            cfg.max_gap = v.gap_mm / 1000;
            const Stopwatch watch;
            const BoundPlanes planes = compute_bound_planes(cloud, grown, cfg);
            const double secs = watch.seconds();
            const std::vector<std::int32_t> found = plane_labels(planes, grown.labels);
            const eval::SegmentationScore f = eval::score_segmentation(cloud.labels, found);
            const eval::SegmentationScore p = eval::score_segmentation(pieces, found);
            std::printf(
                "%6.0f %6.1f %5.0f | %6zu %6.2f | %5llu %4llu %5llu %3llu | %6llu %4llu %5llu "
                "%3llu | "
                "%5.1f | %.3f\n",
                angle, planes.config.max_offset * 1000, planes.config.max_gap * 1000,
                planes.planes.size(), planes.stats.noise * 1000, (unsigned long long)f.faces,
                (unsigned long long)f.over_segmented, (unsigned long long)f.under_segmented,
                (unsigned long long)f.one_to_one, (unsigned long long)p.faces,
                (unsigned long long)p.over_segmented, (unsigned long long)p.under_segmented,
                (unsigned long long)p.one_to_one, 100 * p.points_in_best, secs);
        }
    }
    // Defaults: which faces split or merge, and coverage.
    const BoundPlanes planes = compute_bound_planes(cloud, grown, BoundPlaneConfig{});
    const std::vector<std::int32_t> found = plane_labels(planes, grown.labels);
    const eval::SegmentationScore f = eval::score_segmentation(cloud.labels, found);
    for (const std::int32_t face : f.over_faces) {
        const auto& fc = scene.faces()[static_cast<std::size_t>(face)];
        std::printf("  over-segmented face %d (%s)\n", face,
                    desc.primitives[static_cast<std::size_t>(fc.primitive)].name.c_str());
    }
    for (const std::int32_t seg : f.under_segments)
        std::printf("  under-segmented plane %d (%zu patches, area %.3f m2)\n", seg,
                    planes.planes[static_cast<std::size_t>(seg)].patches.size(),
                    planes.planes[static_cast<std::size_t>(seg)].area);
    std::size_t holes = 0, rings = 0;
    for (const BoundPlane& bp : planes.planes) {
        rings += bp.polygons.size();
        for (const auto& poly : bp.polygons) holes += poly.holes.size();
    }
    std::printf("  defaults: %zu planes, %zu outer rings, %zu holes, area %.3f m2\n",
                planes.planes.size(), rings, holes, planes.stats.area);
    for (std::size_t k = 0; k < std::min<std::size_t>(planes.planes.size(), 12); ++k) {
        const BoundPlane& bp = planes.planes[k];
        std::size_t verts = 0, h = 0;
        for (const auto& poly : bp.polygons) {
            verts += poly.outer.size();
            h += poly.holes.size();
        }
        std::printf(
            "   plane %zu: %llu pts, %zu patches, n=(%.3f %.3f %.3f), area %.4f m2, rms %.2f mm, "
            "%zu rings, %zu verts, %zu holes\n",
            k, (unsigned long long)bp.point_count, bp.patches.size(), bp.normal.x(), bp.normal.y(),
            bp.normal.z(), bp.area, bp.rms * 1000, bp.polygons.size(), verts, h);
    }
    for (const double blast_mm : {12.0, 24.0, 50.0}) {
        CoverageConfig cc;
        cc.blast_radius = blast_mm / 1000;
        const Stopwatch watch;
        const CoveragePlan plan = plan_coverage(planes, grown, cc);
        const double secs = watch.seconds();
        double worst = 1;
        for (const PlaneCoverage& pc : plan.per_plane)
            if (pc.area > 0.01) worst = std::min(worst, pc.covered_fraction);
        std::printf(
            "  blast %4.0f mm: %llu goals, coverage %.4f (worst plane >0.01 m2: %.4f), tool path "
            "%.1f m (sweeps %.1f, %llu transitions %.1f m), %.3f s\n",
            blast_mm, (unsigned long long)plan.stats.goals, plan.stats.coverage, worst,
            plan.stats.tool_path_length, plan.stats.sweep_length,
            (unsigned long long)plan.stats.transitions, plan.stats.transition_length, secs);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> scenes(argv + 1, argv + argc);
    if (scenes.empty()) scenes = {"room-corner", "ibeam-channel"};
    for (const std::string& s : scenes) study(s);
}
