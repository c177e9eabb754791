// Renders a synthetic I-beam channel (two I-beams, deck, floor, as in the paper's Fig. 6) after
// growing surfaces on it, to look at: render_sample [output prefix, default /tmp/render-sample].
// Writes <prefix>.png (iso) and <prefix>-<variant>.png for the other views and styles.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "support/test_support.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene_builder.hpp"

using namespace surfgrow;

namespace {

PointCloud channel_cloud(std::vector<std::int32_t>& truth) {
    std::mt19937_64 rng(7);
    PointCloud cloud;
    const double length = 1.6, height = 0.6, flange = 0.25, gap = 0.9;
    std::int32_t label = 0;
    auto add = [&](const test::Rect& r) {
        test::sample_rect(r, 0.006, 0.3, 0.002, rng, cloud.points, &truth, label++);
    };
    for (double side : {-1.0, 1.0}) {
        for (test::Rect r : test::ibeam_faces(length, height, flange, 0.02, 0.012)) {
            if (r.center.z() > height / 2 - 1e-9) continue;  // top face: under the deck
            r.center.y() += side * gap / 2;
            add(r);
        }
    }
    const Vec3d X = Vec3d::UnitX(), Y = Vec3d::UnitY();
    add({{0, 0, height / 2}, X, Y, length / 2, gap / 2 + flange});  // deck underside
    add({{0, 0, -0.9}, X, Y, length / 2, gap / 2 + flange});        // scaffold floor
    cloud.viewpoint = Vec3d(0, 0, -0.2);                            // the scanner
    return cloud;
}

void write(const std::string& path, const render::Image& image) {
    std::ofstream out(path, std::ios::binary);
    render::write_png(image, out);
    std::printf("wrote %s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    const std::string prefix = argc > 1 ? argv[1] : "/tmp/render-sample";
    std::vector<std::int32_t> truth;
    const PointCloud cloud = channel_cloud(truth);
    const GrowResult result = grow_surfaces(cloud);
    std::printf("%zu points, %zu surfaces\n", cloud.size(), result.surfaces.size());

    render::Scene scene = render::scene_from_surfaces(result.surfaces);
    scene.legend = render::legend_line(result.stats.valid_points, result.surfaces.size(),
                                       result.stats.registered_fraction());
    auto timed = [&](const render::Scene& s, const render::RenderOptions& o) {
        const auto t0 = std::chrono::steady_clock::now();
        render::Image image = render::render_scene(s, o);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        std::printf("render %s: %.0f ms\n", std::string(render::view_name(o.view)).c_str(), ms);
        return image;
    };

    render::RenderOptions opt;
    opt.units = "m";
    write(prefix + ".png", timed(scene, opt));
    render::RenderOptions cut = opt;
    cut.back_faces = render::BackFaces::kCull;
    write(prefix + "-iso-cull.png", timed(scene, cut));
    render::RenderOptions show = opt;
    show.back_faces = render::BackFaces::kShow;
    write(prefix + "-iso-show.png", timed(scene, show));
    for (render::View v : {render::View::kFront, render::View::kSide, render::View::kTop}) {
        render::RenderOptions o = opt;
        o.view = v;
        write(prefix + "-" + std::string(render::view_name(v)) + ".png", timed(scene, o));
    }

    // Bound-plane style: colour by the ground-truth face each surface's home point lies on,
    // with normals and the raw points.
    render::SurfaceStyle style;
    style.normals = true;
    style.groups.resize(result.surfaces.size(), -1);
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (result.labels[i] >= 0)
            style.groups[static_cast<std::size_t>(result.labels[i])] = truth[i];
    render::Scene grouped = render::scene_from_surfaces(result.surfaces, style);
    render::add_points(grouped, cloud, result.labels, result.surfaces.size(), style);
    grouped.legend = scene.legend;
    write(prefix + "-groups-normals-points.png", timed(grouped, opt));
    render::RenderOptions front = opt;
    front.view = render::View::kFront;
    write(prefix + "-groups-front.png", timed(grouped, front));
    return 0;
}
