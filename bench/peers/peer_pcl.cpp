// PCL 1.13 (Debian libpcl-dev) in the peers' harness.
//
//   peer_pcl CLOUD --method region-growing|ransac --out DIR [--k 20] [--tol 0.012]
//            [--angle 15] [--curvature 0.111] [--min-pts 10] [--min-plane 0] [--max-planes 200]
//            [--iterations 1000] [--threads 2] [--min-seconds 1] [--max-repeats 5]
//
// I/O = pcl::io::loadPLYFile. Algorithm:
//   region-growing: kd-tree, NormalEstimationOMP (k nearest), RegionGrowing (same k, smoothness
//     angle, curvature and residual thresholds, min cluster size), then a PCA plane per segment.
//   ransac: SACSegmentation (SACMODEL_PLANE, SAC_RANSAC, coefficients refined) on the points not
//     yet taken, repeated while a plane has at least --min-plane inliers (0: max(min-pts, N/1000))
//     and fewer than --max-planes were found. Plane = the refined model coefficients.
#include <pcl/features/normal_3d_omp.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "peer_common.hpp"
#include "segment_planes.hpp"

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

struct Output {
    std::vector<std::int32_t> labels;
    std::vector<double> planes;
    std::map<std::string, double> stages;
};

Output region_growing(const Cloud::ConstPtr& cloud, const peers::Args& a, int threads) {
    Output o;
    const int k = a.integer("k", 20);
    double t = peers::now_s();
    auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    tree->setInputCloud(cloud);
    o.stages["kdtree"] = peers::now_s() - t;

    t = peers::now_s();
    auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
    pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne(static_cast<unsigned>(threads));
    ne.setInputCloud(cloud);
    ne.setSearchMethod(tree);
    ne.setKSearch(k);
    ne.compute(*normals);
    o.stages["normals"] = peers::now_s() - t;

    t = peers::now_s();
    pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> rg;
    rg.setInputCloud(cloud);
    rg.setInputNormals(normals);
    rg.setSearchMethod(tree);
    rg.setNumberOfNeighbours(k);
    rg.setMinClusterSize(a.integer("min-pts", 10));
    rg.setMaxClusterSize(static_cast<pcl::uindex_t>(cloud->size()));
    rg.setSmoothnessThreshold(static_cast<float>(a.num("angle", 15.0) * std::numbers::pi / 180.0));
    rg.setCurvatureTestFlag(true);
    rg.setCurvatureThreshold(static_cast<float>(a.num("curvature", 1.0 / 9.0)));
    rg.setResidualTestFlag(true);
    rg.setResidualThreshold(static_cast<float>(a.num("tol", 0.012)));
    std::vector<pcl::PointIndices> clusters;
    rg.extract(clusters);
    o.stages["region_growing"] = peers::now_s() - t;

    t = peers::now_s();
    o.labels.assign(cloud->size(), -1);
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        for (const auto i : clusters[c].indices) o.labels[static_cast<std::size_t>(i)] = int(c);
    }
    o.planes = peers::fit_segment_planes(o.labels, clusters.size(), [&](std::size_t i) {
        return (*cloud)[i].getVector3fMap().cast<double>().eval();
    });
    o.stages["planes"] = peers::now_s() - t;
    return o;
}

Output ransac(const Cloud::ConstPtr& cloud, const peers::Args& a, int threads) {
    Output o;
    const std::size_t n = cloud->size();
    const int min_pts = a.integer("min-pts", 10);
    std::size_t min_plane = static_cast<std::size_t>(a.integer("min-plane", 0));
    if (min_plane == 0) min_plane = std::max<std::size_t>(std::size_t(min_pts), n / 1000);
    const int max_planes = a.integer("max-planes", 200);

    pcl::SACSegmentation<pcl::PointXYZ> seg;
    seg.setOptimizeCoefficients(true);
    seg.setModelType(pcl::SACMODEL_PLANE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(a.num("tol", 0.012));
    seg.setMaxIterations(a.integer("iterations", 1000));
    seg.setProbability(0.99);
    seg.setNumberOfThreads(threads);
    seg.setInputCloud(cloud);

    o.labels.assign(n, -1);
    auto remaining = std::make_shared<pcl::Indices>(n);
    for (std::size_t i = 0; i < n; ++i) (*remaining)[i] = static_cast<pcl::index_t>(i);
    while (remaining->size() >= min_plane && int(o.planes.size() / 4) < max_planes) {
        seg.setIndices(remaining);
        pcl::PointIndices inliers;
        pcl::ModelCoefficients coef;
        seg.segment(inliers, coef);
        if (inliers.indices.size() < min_plane || coef.values.size() < 4) break;
        const auto id = static_cast<std::int32_t>(o.planes.size() / 4);
        Eigen::Vector4d p(coef.values[0], coef.values[1], coef.values[2], coef.values[3]);
        p /= p.head<3>().norm();
        o.planes.insert(o.planes.end(), {p[0], p[1], p[2], p[3]});
        for (const auto i : inliers.indices) o.labels[static_cast<std::size_t>(i)] = id;
        auto next = std::make_shared<pcl::Indices>();
        next->reserve(remaining->size() - inliers.indices.size());
        for (const auto i : *remaining) {
            if (o.labels[static_cast<std::size_t>(i)] < 0) next->push_back(i);
        }
        remaining = next;
    }
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const peers::Args args(argc, argv);
        const std::string out = args.str("out", ".");
        peers::Report rep;
        rep.tool = "pcl";
        rep.method = args.str("method", "region-growing");
        rep.input = args.input();
        rep.threads = args.integer("threads", 2);
        rep.baseline_rss = peers::proc_status_bytes("VmRSS");

        const double t0 = peers::now_s();
        auto cloud = std::make_shared<Cloud>();
        if (pcl::io::loadPLYFile(rep.input, *cloud) != 0)
            throw std::runtime_error("cannot read " + rep.input);
        rep.io_seconds = peers::now_s() - t0;
        rep.points = cloud->size();
        rep.input_rss = peers::proc_status_bytes("VmRSS");

        for (const char* key : {"k", "tol", "angle", "curvature", "min-pts", "min-plane",
                                "max-planes", "iterations"}) {
            if (args.has(key)) rep.params[key] = args.num(key, 0);
        }
        Output result;
        rep.algorithm_peak_valid = peers::reset_peak_rss();
        rep.algorithm_seconds = peers::repeat_timed(
            [&](int run) {
                Output o = rep.method == "ransac" ? ransac(cloud, args, rep.threads)
                                                  : region_growing(cloud, args, rep.threads);
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
        std::cout << "pcl " << rep.method << ": " << rep.points << " points -> " << rep.segments
                  << " segments in " << peers::median(rep.algorithm_seconds) << " s\n";
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "peer_pcl: " << e.what() << "\n";
        return 1;
    }
}
