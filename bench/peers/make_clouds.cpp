// The benchmark's input clouds, written once as binary PLY so that every tool reads the same file.
//
//   make_clouds sim  --poses P [--scene NAME] [--length L] [--seed S] --out PREFIX
//                    [--crops N1,N2,...]
//       P fused URG-04LX scans of the I-beam channel (bench/simulated_scans.hpp), 0.5 m apart.
//       Without --length: the built-in 4 m channel, exactly as bench_core simulates it. With it:
//       the same girders L metres long, stiffeners every 0.75 m (for the 10 M-point cloud).
//       --scene: another built-in scene (room-corner, stairs, ...) from its own scan path, as
//       `surfgrow scan --scene NAME --poses P` simulates it (the same points).
//       Writes PREFIX.ply (x y z float, int label = true face id, -1 for none or mixed pixel),
//       PREFIX.normals.f32 (true unit normal per point, NaN where no face) and PREFIX.meta.json
//       (faces, point counts, the neighbourhood statistics the peers' parameters come from).
//       --crops: also PREFIX-N.ply for each N, the N points nearest to the channel's middle
//       along x (same density and structure at every size: the scaling series).
//   make_clouds real IN --out PREFIX [--mu M]
//       A real scan (PCD, PLY, text) as PREFIX.ply (x y z float; non-finite points dropped) and
//       PREFIX.meta.json. mu: given, else the smallest of 12, 24, 48, ... mm at which the median
//       point has at least 15 neighbours within mu (sparse scans need a larger radius; the same
//       mu is given to every tool).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "peer_common.hpp"
#include "simulated_scans.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace {

using surfgrow::PointCloud;
using surfgrow::Vec3d;
using surfgrow::Vec3f;

constexpr int kMinPts = 10;  // the paper's min_pts: the same for every tool

/// Median and 10th/90th percentiles of the number of points within mu (the point itself
/// included, as a k-nearest search counts it), over an evenly strided sample.
nlohmann::json neighbourhood_stats(const PointCloud& cloud, double mu) {
    const surfgrow::CubeIndex index(cloud.points, mu, {}, 0);
    const std::size_t n = cloud.size();
    const std::size_t samples = std::min<std::size_t>(n, 20000);
    std::vector<double> counts;
    counts.reserve(samples);
    for (std::size_t s = 0; s < samples; ++s) {
        const std::size_t i = s * n / samples;
        const Vec3f& p = cloud.points[i];
        if (!p.allFinite()) continue;
        std::size_t c = 0;
        index.for_each_within(p.cast<double>(), mu, [&](std::uint32_t) { ++c; });
        counts.push_back(static_cast<double>(c));
    }
    std::sort(counts.begin(), counts.end());
    auto q = [&](double f) {
        return counts.empty() ? 0.0
                              : counts[static_cast<std::size_t>(f * double(counts.size() - 1))];
    };
    return {{"mu", mu}, {"p10", q(0.1)}, {"median", q(0.5)}, {"p90", q(0.9)}};
}

void write_meta(const std::string& prefix, const nlohmann::json& meta) {
    std::ofstream f(prefix + ".meta.json");
    f << meta.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write " + prefix + ".meta.json");
}

/// A channel of any length: the built-in dimensions, stiffeners every 0.75 m clear of the splice.
surfgrow::scanner::SceneDescription long_channel(double length) {
    surfgrow::scanner::IBeamChannelParams p;
    p.length_m = length;
    p.stiffener_x_m.clear();
    for (double x = -0.75; x > -0.5 * length + 0.3; x -= 0.75) {
        p.stiffener_x_m.push_back(x);
        p.stiffener_x_m.push_back(-x);
    }
    std::sort(p.stiffener_x_m.begin(), p.stiffener_x_m.end());
    return surfgrow::scanner::ibeam_channel_scene(p);
}

std::vector<std::size_t> parse_list(const std::string& s) {
    std::vector<std::size_t> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (!item.empty()) out.push_back(static_cast<std::size_t>(std::stod(item)));
    }
    return out;
}

int cmd_sim(const peers::Args& args) {
    namespace sc = surfgrow::scanner;
    const int poses = args.integer("poses", 1);
    const double length = args.num("length", 0.0);
    const auto seed = static_cast<std::uint64_t>(args.num("seed", 1));
    const std::string prefix = args.str("out", "cloud");
    const double mu = args.num("mu", 0.012);

    const double t0 = peers::now_s();
    const std::string scene_name = args.str("scene", "ibeam-channel");
    if (length > 0 && scene_name != "ibeam-channel")
        throw std::runtime_error("--length is for the I-beam channel only");
    const sc::SceneDescription desc =
        length > 0 ? long_channel(length) : sc::builtin_scene(scene_name);
    const sc::Scene scene(desc);
    const sc::ScanSimulator sim(scene);
    std::vector<sc::RawScan> raws;
    for (auto& s : sim.simulate(sc::scan_poses(desc.scanner, poses), seed))
        raws.push_back(std::move(s.raw));
    PointCloud cloud = sc::fuse_scans(raws);
    raws.clear();
    const double sim_s = peers::now_s() - t0;

    // True normals (as lines: the sign does not matter to the metrics) and points per face.
    const std::size_t n = cloud.size();
    std::vector<float> normals(3 * n, std::numeric_limits<float>::quiet_NaN());
    std::vector<std::uint64_t> per_face(scene.faces().size(), 0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t f = cloud.has_labels() ? cloud.labels[i] : -1;
        if (f < 0 || !cloud.points[i].allFinite()) continue;
        const Vec3d nn = scene.normal_at(f, cloud.points[i].cast<double>() + cloud.offset);
        for (int a = 0; a < 3; ++a) normals[3 * i + a] = static_cast<float>(nn[a]);
        ++per_face[static_cast<std::size_t>(f)];
    }
    peers::write_binary(prefix + ".normals.f32", normals);
    surfgrow::io::write_cloud(prefix + ".ply", cloud);  // binary little-endian, with labels

    nlohmann::json faces = nlohmann::json::array();
    for (const auto& f : scene.faces()) {
        faces.push_back({{"id", f.id},
                         {"planar", f.planar()},
                         {"primitive", desc.primitives[static_cast<std::size_t>(f.primitive)].name},
                         {"points", per_face[static_cast<std::size_t>(f.id)]},
                         {"normal", {f.normal.x(), f.normal.y(), f.normal.z()}}});
    }
    std::size_t no_face = 0;
    for (std::size_t i = 0; i < n; ++i) no_face += cloud.labels[i] < 0 ? 1 : 0;
    const nlohmann::json nb = neighbourhood_stats(cloud, mu);
    nlohmann::json meta = {
        {"kind", "simulated"},
        {"scene", length > 0 ? "ibeam-channel, " + std::to_string(length) + " m"
                  : scene_name == "ibeam-channel" ? std::string("ibeam-channel (built-in, 4 m)")
                                                  : scene_name + " (built-in)"},
        {"poses", poses},
        {"seed", seed},
        {"points", n},
        {"points_without_face", no_face},
        {"truth", true},
        {"mu", mu},
        {"min_pts", kMinPts},
        {"neighbours_within_mu", nb},
        {"simulate_seconds", sim_s},
        {"faces", faces}};
    write_meta(prefix, meta);
    std::cout << prefix << ".ply: " << n << " points, " << poses << " poses, median "
              << nb["median"] << " neighbours within mu, " << sim_s << " s to simulate\n";

    // Crops for the scaling series: the N points nearest the middle along x.
    const std::vector<std::size_t> crops = parse_list(args.str("crops", ""));
    if (!crops.empty()) {
        std::vector<float> ax(n);
        double xmid = 0.0;  // the scan path is centred on x = 0
        for (std::size_t i = 0; i < n; ++i) ax[i] = std::fabs(cloud.points[i].x() - float(xmid));
        std::vector<float> sorted = ax;
        for (const std::size_t want : crops) {
            if (want >= n) continue;
            std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(want), sorted.end());
            const float cut = sorted[want];
            PointCloud c;
            c.offset = cloud.offset;
            for (std::size_t i = 0; i < n && c.points.size() < want; ++i) {
                if (ax[i] < cut) {
                    c.points.push_back(cloud.points[i]);
                    c.labels.push_back(cloud.labels[i]);
                }
            }
            const std::string cp = prefix + "-" + std::to_string(want);
            surfgrow::io::write_cloud(cp + ".ply", c);
            write_meta(cp, {{"kind", "crop"},
                            {"of", prefix + ".ply"},
                            {"points", c.size()},
                            {"half_width_x", cut},
                            {"mu", mu},
                            {"min_pts", kMinPts},
                            {"truth", false}});
            std::cout << cp << ".ply: " << c.size() << " points, |x| < " << cut << " m\n";
        }
    }
    return 0;
}

int cmd_real(const peers::Args& args) {
    const std::string in = args.input();
    const std::string prefix = args.str("out", "real");
    surfgrow::io::ReadOptions ro;
    ro.read_labels = false;
    PointCloud raw = surfgrow::io::read_cloud(in, ro);
    PointCloud cloud;
    cloud.offset = raw.offset;
    cloud.viewpoint = raw.viewpoint;
    for (const Vec3f& p : raw.points) {
        if (p.allFinite()) cloud.points.push_back(p);
    }
    double mu = args.num("mu", 0.0);
    nlohmann::json nb;
    if (mu > 0) {
        nb = neighbourhood_stats(cloud, mu);
    } else {
        for (mu = 0.012;; mu *= 2) {
            nb = neighbourhood_stats(cloud, mu);
            if (nb["median"].get<double>() >= 15 || mu > 0.4) break;
        }
    }
    surfgrow::io::WriteOptions wo;
    wo.write_labels = false;
    surfgrow::io::write_cloud(prefix + ".ply", cloud, wo);
    write_meta(prefix, {{"kind", "real"},
                        {"source", in},
                        {"points", cloud.size()},
                        {"points_dropped_nonfinite", raw.size() - cloud.size()},
                        {"truth", false},
                        {"mu", mu},
                        {"min_pts", kMinPts},
                        {"neighbours_within_mu", nb}});
    std::cout << prefix << ".ply: " << cloud.size() << " points, mu " << mu << ", median "
              << nb["median"] << " neighbours\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc < 2) {
            std::cerr << "usage: make_clouds sim|real ...\n";
            return 2;
        }
        const std::string cmd = argv[1];
        const peers::Args args(argc - 1, argv + 1);
        if (cmd == "sim") return cmd_sim(args);
        if (cmd == "real") return cmd_real(args);
        std::cerr << "make_clouds: unknown command " << cmd << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "make_clouds: " << e.what() << "\n";
        return 1;
    }
}
