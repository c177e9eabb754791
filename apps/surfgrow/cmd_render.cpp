// `surfgrow render OUT -o surfaces.png`: a result's surfaces as disks (paper section 4.3, Figs. 4
// and 6), in any view, with normals, the raw points beneath, or coloured by bound plane.
#include <iostream>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "picture_options.hpp"
#include "result_layers.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/render/png.hpp"
#include "surfgrow/render/renderer.hpp"
#include "surfgrow/render/scene_builder.hpp"

namespace surfgrow::cli {

namespace {

struct RenderArgs {
    std::string dir;
    std::string out;
    std::string view = "iso";
    bool points = false;
    std::string cloud;
    bool normals = false;
    std::string color_by = "surface";
    std::string size = "1600x1200";
    int threads = 0;
    bool quiet = false;
};

void run_render(const RenderArgs& a) {
    // Everything on the command line is checked before any file is read.
    render::RenderOptions options;
    options.view = render::parse_view(a.view);
    std::tie(options.width, options.height) = parse_image_size(a.size, "--size");
    if (a.threads < 0)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--threads must be 0 (all cores) or more, got ", num(a.threads)}));
    options.threads = a.threads;
    if (a.color_by != "surface" && a.color_by != "plane")
        throw Error(ErrorCode::kUsage,
                    cat({"--color-by: '", a.color_by, "' is not surface or plane"}));
    if (a.points && a.cloud.empty())
        throw Error(ErrorCode::kUsage,
                    "--points needs --cloud: the cloud the result was grown from");

    const io::ResultFolder folder = io::read_result_folder(a.dir);
    const io::StoredResult& r = folder.result;
    render::SurfaceStyle style;
    style.normals = a.normals;
    std::string colouring;
    if (a.color_by == "plane") {
        const ResultLayers layers = read_result_layers(folder.dir, r);
        if (!layers.planes)
            throw Error(ErrorCode::kCannotOpen,
                        cat({(folder.dir / "planes.json").string(),
                             ": not found; --color-by plane needs the result's bound planes"}));
        style.groups = plane_of_surface(*layers.planes, r.surfaces.size());
        colouring = ", coloured by bound plane";
    }
    render::Scene scene = render::scene_from_surfaces(r.surfaces, style);
    // The legend of `surfgrow grow`'s picture, so the default render reproduces it exactly.
    scene.legend = cat(
        {render::legend_line(r.stats.points_in, r.stats.surfaces, r.stats.registered_fraction()),
         colouring});
    if (!a.cloud.empty()) {
        const io::GrownCloud g = io::read_grown_cloud(a.cloud, folder);
        render::add_points(scene, g.cloud, g.labels, r.surfaces.size(), style);
    }
    options.units = r.meta.units;
    // Normals face the sensor unless no viewpoint was known; then show both sides of every disk.
    if (r.stats.orientation == OrientationSource::kUp)
        options.back_faces = render::BackFaces::kShow;
    const render::Image image = render::render_scene(scene, options);
    io::write_atomically(a.out, [&](std::ostream& o) { render::write_png(image, o); });
    if (!a.quiet)
        std::cout << a.out << ": " << image.width() << "x" << image.height() << ", "
                  << render::view_name(options.view) << " view, " << r.surfaces.size()
                  << " surfaces" << (scene.points.empty() ? "" : ", ")
                  << (scene.points.empty() ? "" : std::to_string(scene.points.size()) + " points")
                  << std::endl;
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "render", "Draw a result's surfaces as disks in a PNG (paper section 4.3, Figs. 4 and 6)");
    auto a = std::make_shared<RenderArgs>();
    cmd->add_option("result", a->dir, "Result folder written by surfgrow grow")->required();
    cmd->add_option("-o,--out", a->out, "PNG file to write (replaced whole or not at all)")
        ->required();
    cmd->add_option("--view", a->view, "front, side, top or iso")->capture_default_str();
    cmd->add_flag("--points", a->points, "Draw the raw points beneath the disks (needs --cloud)");
    cmd->add_option("--cloud", a->cloud,
                    "The cloud the result was grown from; its points are drawn (implies --points)");
    cmd->add_flag("--normals", a->normals, "Draw each surface's normal as a short red line");
    cmd->add_option("--color-by", a->color_by,
                    "surface: a colour per surface; plane: per bound plane (needs planes.json)")
        ->capture_default_str();
    cmd->add_option("--size", a->size, "Picture size in pixels, WIDTHxHEIGHT")
        ->capture_default_str();
    add_threads_option(*cmd, a->threads, "Threads (0 = all cores); the picture is the same");
    cmd->add_flag("-q,--quiet", a->quiet, "No summary line on stdout");
    cmd->callback([a] { run_render(*a); });
}

}  // namespace surfgrow::cli
