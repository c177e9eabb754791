// The study behind the disk test's defaults (docs/algorithm.md, "The plane test"): every built-in
// scene, at the optical offsets 0 and 40 mm, one pose and three fused with small pose errors,
// grown with the defaults (or the settings given); the registered share by range band and the
// tails of the per-point normal error, for patches and through the bound planes.
// Run: build/bench/robustness_study [--paper] [--scene NAME] [--spread S] [--incidence DEG]
//      [--sigmas K] [--mu-max FACTOR] [--alpha A] [--pool-radius MU] [--pool-angle DEG]
//      [--thickness K] [--no-attach] [--pose-seed S] [--poses N] [--min-new N]
//      [--veil-angle DEG] (the mixed-pixel filter when fusing: scanner/veil_filter.hpp)
// Where the tail lies, by environment variable: STUDY_TIMES (stages and counters), STUDY_NOISE
// (the noise and layer profiles), STUDY_BANDS (by range band and incidence), STUDY_KINDS (how the
// points > 45 deg off went wrong; with STUDY_MIXED, the surfaces mostly of mixed pixels),
// STUDY_MISSED (each face not detected, and the bound planes that hold it), STUDY_PLANE_ERR (the
// bound planes more than 2 degrees, or STUDY_PLANE_ERR=D degrees, off their face;
// STUDY_PLANE_PATCHES: their patches of other faces), STUDY_NO_BRIDGE (bound planes without gap
// bridging), STUDY_FACES (by face; with STUDY_SURFACES the worst surfaces, STUDY_AT=x,y,z the
// points near a spot, STUDY_UNREG_FACE=id a face's unregistered points, STUDY_DUMP=id a surface's
// ball).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/face_detection.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

using namespace surfgrow;

namespace {

std::uint64_t pose_seed = 7;  // the pose errors: as the tests draw them
// How many poses the fused rows fuse (--poses): 3, as the scene tests.
int fused_poses = 3;
// How the scans are fused (--veil-angle: mixed pixels dropped; off, as the tests fuse).
scanner::FuseOptions fusing;

// As tests/eval/test_builtin_scenes.cpp scans: three poses along the scene's scan path; one scan
// is the middle one, three are fused with recorded poses 2 mm and 0.1 degree off, as a robot's are.
PointCloud scan(const scanner::Scene& scene, double offset_m, int poses, std::uint64_t seed) {
    scanner::ScannerSpec spec;
    spec.optical_offset_m = Vec3d(0, 0, offset_m);
    const scanner::ScanSimulator sim(scene, spec);
    std::vector<scanner::RawScan> raws;
    // One scan is the middle of three, whatever the fused rows fuse.
    const int count = poses == 1 ? 3 : poses;
    for (auto& s : sim.simulate(scanner::scan_poses(scene.description().scanner, count), seed))
        raws.push_back(std::move(s.raw));
    // STUDY_SINGLE=k: the single rows from scan k of the three instead (0, 1 or 2).
    std::size_t single = 1;
    if (const char* k = std::getenv("STUDY_SINGLE"))
        single = std::min<std::size_t>(2, std::strtoul(k, nullptr, 10));
    if (poses == 1)
        return scanner::fuse_scans(std::span<const scanner::RawScan>(&raws[single], 1), fusing);
    for (std::size_t k = 0; k < raws.size(); ++k)
        raws[k].pose = scanner::perturb_pose(raws[k].pose, 0.002, scanner::deg_to_rad(0.1),
                                             mix_seed(pose_seed, k));
    return scanner::fuse_scans(raws, fusing);
}

}  // namespace

int main(int argc, char** argv) {
    GrowerConfig config;
    std::vector<std::string> scenes = scanner::builtin_scene_names();
    // STUDY_NOISE_SEED=S: the scans' noise from seed S instead of 1 (the tests' draw).
    const char* noise_env = std::getenv("STUDY_NOISE_SEED");
    const std::uint64_t noise_seed = noise_env ? std::strtoull(noise_env, nullptr, 10) : 1;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        const char* next = a + 1 < argc ? argv[a + 1] : "0";
        if (arg == "--paper") {
            config.plane_test = PlaneTest::kPaper;
            config.adaptive_factor = 2.0;
        } else if (arg == "--scene") {
            scenes = {next};
            ++a;
        } else if (arg == "--spread") {
            config.min_spread = std::atof(next);
            ++a;
        } else if (arg == "--incidence") {
            config.max_incidence_deg = std::atof(next);
            ++a;
        } else if (arg == "--sigmas") {
            config.noise_sigmas = std::atof(next);
            ++a;
        } else if (arg == "--mu-max") {
            config.adaptive_factor = std::atof(next);
            ++a;
        } else if (arg == "--pool-radius") {
            config.pool_radius = std::atof(next) * config.mu;
            ++a;
        } else if (arg == "--pool-angle") {
            config.pool_angle_deg = std::atof(next);
            ++a;
        } else if (arg == "--thickness") {
            config.thickness_sigmas = std::atof(next);
            ++a;
        } else if (arg == "--no-attach") {
            config.attach_leftovers = false;
        } else if (arg == "--poses") {
            fused_poses = std::max(2, std::atoi(next));
            ++a;
        } else if (arg == "--pose-seed") {
            pose_seed = std::strtoull(next, nullptr, 10);
            ++a;
        } else if (arg == "--alpha") {
            config.alpha = std::atof(next);
            ++a;
        } else if (arg == "--veil-angle") {
            fusing.veil.angle_deg = std::atof(next);
            ++a;
        } else if (arg == "--min-new") {
            config.min_new_points = std::atoi(next);
            ++a;
        } else {
            std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
            return 2;
        }
    }
    std::printf("%-14s %4s %5s %8s | %7s %7s | %6s %6s %6s %6s | %6s %6s | %5s | %6s\n", "scene",
                "off", "poses", "points", "reg", "worst", "med", "p95", ">10", ">45", "pl.p95",
                "pl>45", "faces", "grow s");
    for (const std::string& name : scenes) {
        const scanner::Scene scene(scanner::builtin_scene(name));
        // The name of the primitive face f belongs to ("none" for points on no face).
        const auto face_name = [&](auto f) {
            if (f < 0) return "none";
            const auto& face = scene.faces()[static_cast<std::size_t>(f)];
            return scene.description()
                .primitives[static_cast<std::size_t>(face.primitive)]
                .name.c_str();
        };
        for (const double offset : {0.0, 0.040}) {
            for (const int poses : {1, fused_poses}) {
                const PointCloud cloud = scan(scene, offset, poses, noise_seed);
                const Stopwatch watch;
                const GrowResult r = grow_surfaces(cloud, config);
                const double secs = watch.seconds();
                eval::EvalReport e = eval::evaluate(cloud, r, scene.faces());
                BoundPlaneConfig pc;
                pc.mu = config.mu;
                if (std::getenv("STUDY_NO_BRIDGE")) pc.max_gap = -1;
                const BoundPlanes planes = compute_bound_planes(cloud, r, pc);
                eval::add_plane_figures(e, cloud, eval::GrowOutcome{r.surfaces, r.labels, &r.stats},
                                        planes, scene.faces());
                std::printf(
                    "%-14s %4.0f %5d %8zu | %6.2f%% %6.2f%% | %6.2f %6.2f %5.2f%% %5.2f%% | %6.2f "
                    "%5.2f%% | %2llu/%-2llu | %6.3f\n",
                    name.c_str(), offset * 1000, poses, cloud.size(), 100 * e.planar.fraction(),
                    100 * e.worst_band_planar(), e.normal_deg.median, e.normal_deg.p95,
                    100 * e.normal_over_10, 100 * e.normal_over_45, e.planes.normal_deg.p95,
                    100 * e.planes.over_45,
                    static_cast<unsigned long long>(e.planes.faces_detected),
                    static_cast<unsigned long long>(e.planes.faces_scored), secs);
                if (std::getenv("STUDY_TIMES"))
                    std::printf(
                        "      index %.3f grow %.3f attach %.3f finish %.3f s; tried %llu, "
                        "sparse %llu, nonplanar %llu, covered %llu, adapted %llu, "
                        "surfaces %llu, lone %llu\n",
                        r.stats.seconds.index, r.stats.seconds.grow, r.stats.seconds.attach,
                        r.stats.seconds.finish,
                        static_cast<unsigned long long>(r.stats.homes_tried),
                        static_cast<unsigned long long>(r.stats.rejected_sparse),
                        static_cast<unsigned long long>(r.stats.rejected_nonplanar),
                        static_cast<unsigned long long>(r.stats.rejected_covered),
                        static_cast<unsigned long long>(r.stats.adapted_surfaces),
                        static_cast<unsigned long long>(r.stats.surfaces),
                        static_cast<unsigned long long>(r.stats.lone_surfaces));
                if (std::getenv("STUDY_PLANE_ERR")) {
                    const double given = std::atof(std::getenv("STUDY_PLANE_ERR"));
                    const double plane_err_deg = given > 0 ? given : 2.0;
                    // Each bound plane of over 500 points more than that many degrees off the face
                    // most of its points lie on: the faces it holds; with STUDY_PLANE_PATCHES, its
                    // patches whose points lie mostly elsewhere.
                    const std::vector<std::int32_t> pl = plane_labels(planes, r.labels);
                    std::map<std::int32_t, std::map<std::int32_t, std::uint64_t>> by_plane,
                        by_patch;
                    // (plane, face) -> the sum of their common points: the face's mean there.
                    std::map<std::int64_t, Vec3d> sum;
                    for (std::size_t i = 0; i < cloud.size(); ++i) {
                        if (pl[i] < 0) continue;
                        ++by_plane[pl[i]][cloud.labels[i]];
                        ++by_patch[r.labels[i]][cloud.labels[i]];
                        const std::int64_t key = std::int64_t{pl[i]} * 65536 + cloud.labels[i];
                        sum.try_emplace(key, Vec3d::Zero()).first->second +=
                            cloud.points[i].cast<double>();
                    }
                    const auto majority = [](const std::map<std::int32_t, std::uint64_t>& c) {
                        std::pair<std::int32_t, std::uint64_t> top{-1, 0};
                        for (auto [f, k] : c)
                            if (f >= 0 && k > top.second) top = {f, k};
                        return top;
                    };
                    for (auto& [q, c] : by_plane) {
                        const auto [face, top] = majority(c);
                        std::uint64_t total = 0;
                        for (auto [f, k] : c) total += k;
                        if (face < 0 || !scene.faces()[std::size_t(face)].planar() || total <= 500)
                            continue;
                        const Vec3d o = sum.at(std::int64_t{q} * 65536 + face) / double(top);
                        const Vec3d truth = scene.normal_at(face, o);
                        const BoundPlane& bp = planes.planes[std::size_t(q)];
                        const auto off_deg = [&](const Vec3d& n) {
                            return std::acos(std::min(1.0, std::abs(truth.dot(n)))) * 180 / M_PI;
                        };
                        if (off_deg(bp.normal) <= plane_err_deg) continue;
                        std::printf("      plane %d: %llu points, %.2f deg off face %d (%s):", q,
                                    (unsigned long long)total, off_deg(bp.normal), face,
                                    face_name(face));
                        for (auto [f, k] : c)
                            if (k * 50 > total)
                                std::printf(" %s %llu", f >= 0 ? face_name(f) : "none",
                                            (unsigned long long)k);
                        std::printf("\n");
                        if (!std::getenv("STUDY_PLANE_PATCHES")) continue;
                        for (const std::uint32_t sid : bp.patches) {
                            const auto [pf, pk] = majority(by_patch[std::int32_t(sid)]);
                            if (pf == face) continue;
                            const Surface& sf = r.surfaces[sid];
                            std::printf(
                                "        patch %u: %u points, %llu of face %d, %.1f deg off, "
                                "centroid %.1f mm off the face, r %.0f mm, home %.3f %.3f %.3f\n",
                                sid, sf.point_count, (unsigned long long)pk, pf, off_deg(sf.normal),
                                1000 * truth.dot(sf.centroid - o), 1000 * sf.radius, sf.home.x(),
                                sf.home.y(), sf.home.z());
                        }
                    }
                }
                if (std::getenv("STUDY_MISSED")) {
                    // Each planar face not correctly detected: the bound planes holding its
                    // points, with their share of the face and of their own points on it.
                    std::vector<std::uint8_t> planar(scene.faces().size(), 0);
                    for (std::size_t f = 0; f < planar.size(); ++f)
                        planar[f] = scene.faces()[f].planar() ? 1 : 0;
                    const std::vector<std::int32_t> pl = plane_labels(planes, r.labels);
                    const eval::FaceDetection d =
                        eval::correct_detections(cloud.labels, pl, 0.8, 500, planar);
                    std::map<std::int32_t, std::uint64_t> plane_size;
                    for (const std::int32_t q : pl) ++plane_size[q];
                    for (const std::int32_t f : d.missed) {
                        std::map<std::int32_t, std::uint64_t> on;
                        std::uint64_t total = 0;
                        for (std::size_t i = 0; i < cloud.size(); ++i)
                            if (cloud.labels[i] == f) ++on[pl[i]], ++total;
                        std::printf("      missed face %d (%s), %llu points:", f, face_name(f),
                                    (unsigned long long)total);
                        for (auto [q, c] : on)
                            if (c * 20 >= total)
                                std::printf(
                                    " plane %d: %.0f%% of it, %.0f%% of its points", q,
                                    100.0 * double(c) / double(total),
                                    q < 0 ? 0.0 : 100.0 * double(c) / double(plane_size[q]));
                        std::printf("\n");
                        // The composition of the plane holding most of it.
                        std::int32_t top = -1;
                        std::uint64_t top_count = 0;
                        for (auto [q, c] : on)
                            if (q >= 0 && c > top_count) top = q, top_count = c;
                        if (top < 0) continue;
                        std::map<std::int32_t, std::uint64_t> comp;
                        for (std::size_t i = 0; i < cloud.size(); ++i)
                            if (pl[i] == top) ++comp[cloud.labels[i]];
                        const BoundPlane& bp = planes.planes[std::size_t(top)];
                        if (std::getenv("STUDY_MISSED_DIST")) {
                            // The plane's points on no face, by whole mm off it (7: 7 or more).
                            int hist[8] = {0, 0, 0, 0, 0, 0, 0, 0};
                            for (std::size_t i = 0; i < cloud.size(); ++i) {
                                if (pl[i] != top || cloud.labels[i] >= 0) continue;
                                const double off =
                                    std::abs(bp.normal.dot(cloud.points[i].cast<double>() -
                                                           bp.centroid)) *
                                    1000;
                                ++hist[std::min(7, int(off))];
                            }
                            std::printf("        no-face points by mm off the plane (rms %.1f):",
                                        bp.rms * 1000);
                            for (int h : hist) std::printf(" %d", h);
                            std::printf("\n");
                        }
                        if (std::getenv("STUDY_MISSED_PATCHES")) {
                            // Face votes of each member patch, in one pass over the cloud.
                            std::map<std::int32_t, std::map<std::int32_t, int>> votes;
                            for (const std::uint32_t k : bp.patches) votes[std::int32_t(k)];
                            for (std::size_t i = 0; i < cloud.size(); ++i)
                                if (auto v = votes.find(r.labels[i]); v != votes.end())
                                    ++v->second[cloud.labels[i]];
                            for (const std::uint32_t k : bp.patches) {
                                const Surface& s = r.surfaces[k];
                                std::printf(
                                    "        patch %u: %u pts, r %.0f, angle %.1f, off "
                                    "%.1f mm, home %.3f %.3f %.3f:",
                                    k, s.point_count, s.radius * 1000,
                                    axis_angle_between(s.normal, bp.normal) * 180 / M_PI,
                                    1000 * bp.normal.dot(s.centroid - bp.centroid), s.home.x(),
                                    s.home.y(), s.home.z());
                                for (auto [fid, c] : votes[std::int32_t(k)])
                                    std::printf(" f%d:%d", fid, c);
                                std::printf("\n");
                            }
                        }
                        std::printf("        plane %d holds:", top);
                        for (auto [t, c] : comp)
                            if (c * 50 >= plane_size[top])
                                std::printf(" face %d (%s) %.0f%%", t, face_name(t),
                                            100.0 * double(c) / double(plane_size[top]));
                        std::printf("\n");
                    }
                }
                if (std::getenv("STUDY_NOISE")) {
                    std::printf("      noise sigma (band %.2f m):", r.stats.noise_band);
                    for (double v : r.stats.noise_sigma) std::printf(" %.1f", v * 1000);
                    std::printf("\n      layer sigma (band %.2f m):", r.stats.layer_band);
                    for (double v : r.stats.layer_sigma) std::printf(" %.1f", v * 1000);
                    std::printf("\n");
                }
                if (std::getenv("STUDY_BANDS")) {
                    for (const eval::BandReport& b : e.bands) {
                        if (b.planar.points < 200) continue;
                        std::printf(
                            "      %.1f-%.1f m: %7llu planar, %6.2f%% reg, p95 %6.2f, >10 "
                            "%5.2f%%, >45 %5.2f%%\n",
                            b.from_m, b.to_m, static_cast<unsigned long long>(b.planar.points),
                            100 * b.planar.fraction(), b.normal_deg.p95, 100 * b.over_10,
                            100 * b.over_45);
                    }
                    for (const eval::IncidenceReport& b : e.incidence) {
                        if (b.planar.points < 200) continue;
                        std::printf(
                            "      incidence %2.0f-%2.0f: %7llu planar, %6.2f%% reg, p95 "
                            "%6.2f, >45 %5.2f%%\n",
                            b.from_deg, b.to_deg, static_cast<unsigned long long>(b.planar.points),
                            100 * b.planar.fraction(), b.normal_deg.p95, 100 * b.over_45);
                    }
                }
                if (std::getenv("STUDY_KINDS")) {
                    // Each point > 45 deg off: is its surface wrong for its own majority face
                    // (a fit across an edge), or right for another face (a point taken across
                    // an edge)? And its distance to its surface's plane in noise sigmas.
                    std::vector<std::map<std::int32_t, std::uint64_t>> votes(r.surfaces.size());
                    for (std::size_t i = 0; i < cloud.size(); ++i)
                        if (r.labels[i] >= 0) ++votes[std::size_t(r.labels[i])][cloud.labels[i]];
                    std::vector<std::int32_t> major(r.surfaces.size(), -1);
                    for (std::size_t k = 0; k < votes.size(); ++k) {
                        std::uint64_t best = 0;
                        for (auto [f, c] : votes[k])
                            if (c > best) best = c, major[k] = f;
                    }
                    std::uint64_t wrong_fit = 0, taken = 0, unknown = 0, wrong_fit_pts = 0,
                                  unknown_mixed = 0;
                    std::vector<bool> seen(r.surfaces.size(), false);
                    for (std::size_t i = 0; i < cloud.size(); ++i) {
                        const std::int32_t f = cloud.labels[i], l = r.labels[i];
                        if (f < 0 || l < 0 || !scene.faces()[std::size_t(f)].planar()) continue;
                        const Surface& s = r.surfaces[std::size_t(l)];
                        const Vec3d p = cloud.points[i].cast<double>();
                        if (axis_angle_between(s.normal, scene.normal_at(f, p)) * 180 / M_PI <= 45)
                            continue;
                        const std::int32_t m = major[std::size_t(l)];
                        if (m < 0 || !scene.faces()[std::size_t(m)].planar()) {
                            ++unknown;
                            if (m < 0) ++unknown_mixed;
                            continue;
                        }
                        const double em =
                            axis_angle_between(s.normal, scene.normal_at(m, s.home)) * 180 / M_PI;
                        if (em > 20) {
                            ++wrong_fit;
                            if (!seen[std::size_t(l)]) seen[std::size_t(l)] = true, ++wrong_fit_pts;
                        } else {
                            ++taken;
                        }
                    }
                    if (std::getenv("STUDY_MIXED")) {
                        // The surfaces made mostly of points on no face (mixed pixels): their
                        // incidence (each member's line of sight from its own scan), size and
                        // shape, and the patches around them as the minority rule weighs them:
                        // homes within the pooling radius, those in the surface's plane (angle and
                        // offset as pooling tests them) and the plane's share of the others'
                        // neighbourhoods. The rule judges only surfaces with 3 patches around.
                        const double pool_cos = std::cos(config.pool_angle_deg * M_PI / 180);
                        for (std::size_t k = 0; k < r.surfaces.size(); ++k) {
                            if (major[k] >= 0) continue;
                            const Surface& s = r.surfaces[k];
                            std::uint64_t planar_pts = 0;
                            for (auto [f, cnt] : votes[k])
                                if (f >= 0) planar_pts += cnt;
                            if (planar_pts < 3) continue;
                            double inc = 0, range = 0;
                            std::uint64_t members = 0;
                            for (std::size_t i = 0; i < cloud.size(); ++i) {
                                if (r.labels[i] != static_cast<std::int32_t>(k)) continue;
                                const std::size_t sc =
                                    cloud.scan_index.empty() ? 0 : cloud.scan_index[i];
                                const Vec3d ray =
                                    cloud.points[i].cast<double>() - cloud.scan_origins[sc];
                                inc += std::acos(std::min(
                                           1.0, std::abs(s.normal.dot(ray.normalized())))) *
                                       180 / M_PI;
                                range += ray.norm();
                                ++members;
                            }
                            int around = 0, coplanar = 0;
                            double in_plane = s.neighbours, elsewhere = 0;
                            for (std::size_t t = 0; t < r.surfaces.size(); ++t) {
                                const Surface& b = r.surfaces[t];
                                if (t == k || (b.home - s.home).norm() > config.pooling_radius())
                                    continue;
                                ++around;
                                if (std::abs(b.normal.dot(s.normal)) < pool_cos) {
                                    elsewhere += b.neighbours;
                                    continue;
                                }
                                const double sigma =
                                    std::sqrt(std::max({s.eigenvalues[0], b.eigenvalues[0], 0.0}));
                                const double off =
                                    std::clamp(3 * sigma, config.mu / 10, config.mu / 2);
                                const Vec3d d = b.centroid - s.centroid;
                                if (std::abs(s.normal.dot(d)) > off ||
                                    std::abs(b.normal.dot(d)) > off)
                                    continue;
                                ++coplanar;
                                in_plane += b.neighbours;
                            }
                            std::printf(
                                "      mixed surface %zu: %u members (%llu on faces), r %.0f "
                                "mm, tol %.1f, ev %.2f %.2f %.2f, incidence %.0f deg, range "
                                "%.2f; around %d, coplanar %d, plane share %.2f\n",
                                k, s.point_count, (unsigned long long)planar_pts, s.radius * 1000,
                                s.tolerance * 1000, s.eigenvalues[0] * 1e6, s.eigenvalues[1] * 1e6,
                                s.eigenvalues[2] * 1e6, members ? inc / double(members) : 0.0,
                                members ? range / double(members) : 0.0, around, coplanar,
                                elsewhere > 0 ? in_plane / elsewhere : 0.0);
                        }
                    }
                    std::printf(
                        "      >45 kinds: fit wrong for its own face %llu pts (%llu "
                        "surfaces), point taken across an edge %llu, majority unknown "
                        "%llu (on no face %llu)\n",
                        (unsigned long long)wrong_fit, (unsigned long long)wrong_fit_pts,
                        (unsigned long long)taken, (unsigned long long)unknown,
                        (unsigned long long)unknown_mixed);
                }
                if (std::getenv("STUDY_FACES")) {
                    // Where the points more than 45 degrees off lie: by face, with the radius of
                    // the surfaces that hold them and their range.
                    std::vector<std::uint64_t> bad(scene.faces().size(), 0), all(bad.size(), 0);
                    std::vector<double> radius_sum(bad.size(), 0), range_sum(bad.size(), 0);
                    std::vector<std::uint64_t> unreg(bad.size(), 0), total(bad.size(), 0);
                    for (std::size_t i = 0; i < cloud.size(); ++i) {
                        const std::int32_t f = cloud.labels[i], l = r.labels[i];
                        if (f >= 0 && is_finite(cloud.points[i])) {
                            ++total[std::size_t(f)];
                            if (l < 0) ++unreg[std::size_t(f)];
                        }
                        if (f < 0 || l < 0 || !scene.faces()[std::size_t(f)].planar()) continue;
                        const Surface& s = r.surfaces[std::size_t(l)];
                        const Vec3d p = cloud.points[i].cast<double>();
                        ++all[std::size_t(f)];
                        const double err =
                            axis_angle_between(s.normal, scene.normal_at(f, p)) * 180 / M_PI;
                        if (err <= 45) continue;
                        ++bad[std::size_t(f)];
                        radius_sum[std::size_t(f)] += s.radius;
                        range_sum[std::size_t(f)] +=
                            (p - cloud.scan_origins[cloud.scan_index[i]]).norm();
                    }
                    if (std::getenv("STUDY_SURFACES")) {
                        std::vector<std::uint64_t> bad_of(r.surfaces.size(), 0);
                        std::vector<std::int32_t> face_of(r.surfaces.size(), -1);
                        for (std::size_t i = 0; i < cloud.size(); ++i) {
                            const std::int32_t f = cloud.labels[i], l = r.labels[i];
                            if (f < 0 || l < 0 || !scene.faces()[std::size_t(f)].planar()) continue;
                            const Surface& s = r.surfaces[std::size_t(l)];
                            const double err =
                                axis_angle_between(
                                    s.normal, scene.normal_at(f, cloud.points[i].cast<double>())) *
                                180 / M_PI;
                            if (err > 45) {
                                ++bad_of[std::size_t(l)];
                                face_of[std::size_t(l)] = f;
                            }
                        }
                        std::vector<std::size_t> ids(r.surfaces.size());
                        for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = k;
                        std::partial_sort(
                            ids.begin(), ids.begin() + 12, ids.end(),
                            [&](std::size_t a, std::size_t b) { return bad_of[a] > bad_of[b]; });
                        for (std::size_t q = 0; q < 12; ++q) {
                            const Surface& s = r.surfaces[ids[q]];
                            std::printf(
                                "      surface %zu: %llu bad of %u (face %d), r %.0f mm, "
                                "n %u, tol %.1f mm, ev %.2f %.2f %.2f mm2, home %.3f "
                                "%.3f %.3f, normal %.2f %.2f %.2f\n",
                                ids[q], static_cast<unsigned long long>(bad_of[ids[q]]),
                                s.point_count, face_of[ids[q]], s.radius * 1000, s.neighbours,
                                s.tolerance * 1000, s.eigenvalues[0] * 1e6, s.eigenvalues[1] * 1e6,
                                s.eigenvalues[2] * 1e6, s.home.x(), s.home.y(), s.home.z(),
                                s.normal.x(), s.normal.y(), s.normal.z());
                        }
                    }
                    if (const char* at = std::getenv("STUDY_AT")) {
                        // Every point within 30 mm of x,y,z: its scan, truth, label and the
                        // distance to its own surface's plane, and to the nearest surface's.
                        double x, y, z;
                        std::sscanf(at, "%lf,%lf,%lf", &x, &y, &z);
                        const Vec3d c(x, y, z);
                        for (std::size_t i = 0; i < cloud.size(); ++i) {
                            const Vec3d p = cloud.points[i].cast<double>();
                            if ((p - c).norm() > 0.03) continue;
                            const std::int32_t l = r.labels[i];
                            double d = -1, tol = -1, rad = -1;
                            if (l >= 0) {
                                const Surface& s = r.surfaces[std::size_t(l)];
                                d = std::abs(s.normal.dot(p - s.centroid));
                                tol = s.tolerance;
                                rad = s.radius;
                            }
                            std::printf(
                                "AT %7.1f %7.1f %7.1f scan %u truth %3d label %6d d %.1f "
                                "tol %.1f r %.0f\n",
                                1000 * (p.x() - x), 1000 * (p.y() - y), 1000 * (p.z() - z),
                                cloud.scan_index[i], cloud.labels[i], l, 1000 * d, 1000 * tol,
                                1000 * rad);
                        }
                    }
                    if (const char* band = std::getenv("STUDY_UNREG_BAND")) {
                        // Unregistered planar points within a range band, by face.
                        double lo = 0, hi = 0;
                        if (std::sscanf(band, "%lf,%lf", &lo, &hi) == 2) {
                            std::map<std::int32_t, std::pair<std::uint64_t, std::uint64_t>> by;
                            for (std::size_t i = 0; i < cloud.size(); ++i) {
                                const std::int32_t f = cloud.labels[i];
                                if (f < 0 || !scene.faces()[std::size_t(f)].planar()) continue;
                                const Vec3d p = cloud.points[i].cast<double>();
                                const double range =
                                    (p - cloud.scan_origins[cloud.scan_index[i]]).norm();
                                if (range < lo || range >= hi) continue;
                                ++by[f].second;
                                if (r.labels[i] < 0) ++by[f].first;
                            }
                            for (auto [f, c] : by)
                                if (c.first > 0)
                                    std::printf(
                                        "      band face %d (%s): %llu of %llu unregistered\n", f,
                                        face_name(f), (unsigned long long)c.first,
                                        (unsigned long long)c.second);
                        }
                    }
                    if (const char* uf = std::getenv("STUDY_UNREG_FACE")) {
                        const std::int32_t face = std::atoi(uf);
                        for (std::size_t i = 0; i < cloud.size(); ++i) {
                            if (cloud.labels[i] != face || r.labels[i] >= 0) continue;
                            const Vec3d p = cloud.points[i].cast<double>();
                            std::printf("UNREG %.3f %.3f %.3f scan %u range %.2f\n", p.x(), p.y(),
                                        p.z(), cloud.scan_index[i],
                                        (p - cloud.scan_origins[cloud.scan_index[i]]).norm());
                        }
                    }
                    if (const char* dump = std::getenv("STUDY_DUMP")) {
                        const auto id = static_cast<std::size_t>(std::atoll(dump));
                        if (id < r.surfaces.size()) {
                            const Surface& s = r.surfaces[id];
                            const Vec3d origin = cloud.scan_origins[0];
                            for (std::size_t i = 0; i < cloud.size(); ++i) {
                                const Vec3d p = cloud.points[i].cast<double>();
                                if ((p - s.home).norm() > s.radius) continue;
                                const Vec3d q = p - s.home;
                                std::printf(
                                    "DUMP %8.2f %8.2f %8.2f truth %4d label %6d scan %u "
                                    "range %.4f\n",
                                    q.x() * 1000, q.y() * 1000, q.z() * 1000, cloud.labels[i],
                                    r.labels[i], cloud.scan_index[i], (p - origin).norm());
                            }
                        }
                    }
                    for (std::size_t f = 0; f < bad.size(); ++f) {
                        if (unreg[f] < 50) continue;
                        std::printf("      face %zu (%s): %llu of %llu unregistered\n", f,
                                    face_name(f), static_cast<unsigned long long>(unreg[f]),
                                    static_cast<unsigned long long>(total[f]));
                    }
                    for (std::size_t f = 0; f < bad.size(); ++f) {
                        if (bad[f] < 50) continue;
                        std::printf(
                            "      face %zu (%s): %llu of %llu > 45 deg, radius %.0f mm, "
                            "range %.2f m\n",
                            f, face_name(f), static_cast<unsigned long long>(bad[f]),
                            static_cast<unsigned long long>(all[f]),
                            1000 * radius_sum[f] / double(bad[f]), range_sum[f] / double(bad[f]));
                    }
                }
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
