// `surfgrow render OUT -o surfaces.png`: a result's surfaces as disks (paper section 4.3, Figs. 4
// and 6), in any view, with normals, the raw points beneath, or coloured by bound plane.
#include <iostream>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "picture_options.hpp"
#include "result_layers.hpp"
#include "surfaces_picture.hpp"
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
    bool no_normals = false;
    std::string color_by = "auto";
    std::string frame = "bulk";
    bool close_up = false;
    std::string size = "1600x1200";
    int threads = 0;
    bool quiet = false;
};

void run_render(const RenderArgs& a) {
    // Everything on the command line is checked before any file is read.
    const render::View view = render::parse_view(a.view);
    const render::Framing framing = render::parse_framing(a.frame);
    const auto [width, height] = parse_image_size(a.size, "--size");
    if (a.threads < 0)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--threads must be 0 (all cores) or more, got ", num(a.threads)}));
    if (a.color_by != "auto" && a.color_by != "surface" && a.color_by != "plane")
        throw Error(ErrorCode::kUsage,
                    cat({"--color-by: '", a.color_by, "' is not auto, surface or plane"}));
    if (a.points && a.cloud.empty())
        throw Error(ErrorCode::kUsage,
                    "--points needs --cloud: the cloud the result was grown from");
    if (a.normals && a.no_normals)
        throw Error(ErrorCode::kUsage, "--normals and --no-normals contradict each other");
    if (a.close_up && a.color_by == "surface")
        throw Error(ErrorCode::kUsage,
                    "--close-up finds a corner where bound planes meet: not with --color-by "
                    "surface");

    const io::ResultFolder folder = io::read_result_folder(a.dir);
    const io::StoredResult& r = folder.result;
    std::vector<std::int32_t> planes;
    if (a.color_by != "surface" || a.close_up) {
        const auto outlines = read_plane_outlines(folder.dir, r);
        if (outlines)
            planes = plane_of_surface(*outlines, r.surfaces.size());
        else if (a.color_by == "plane" || a.close_up)
            throw Error(ErrorCode::kCannotOpen,
                        cat({(folder.dir / "planes.json").string(), ": not found; ",
                             a.close_up ? "--close-up" : "--color-by plane",
                             " needs the result's bound planes"}));
    }
    // The picture `surfgrow grow` writes, so the default render reproduces it exactly.
    SurfacesPicture picture =
        surfaces_picture(r.surfaces, r.stats, planes, r.meta.units, a.threads);
    if (a.no_normals) picture.scene.lines.clear();
    if (a.normals) picture.options.normal_min_radius = 0;
    picture.options.view = view;
    picture.options.framing = framing;
    picture.options.width = width;
    picture.options.height = height;
    if (a.close_up && !make_corner_close_up(picture, planes))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({a.dir,
                         ": no corner where bound planes of different orientation meet, "
                         "for --close-up"}));
    if (!a.cloud.empty()) {
        const io::GrownCloud g = io::read_grown_cloud(a.cloud, folder);
        render::add_points(picture.scene, g.cloud, g.labels, r.surfaces.size());
    }
    const render::Image image = render::render_scene(picture.scene, picture.options);
    io::write_atomically(a.out, [&](std::ostream& o) { render::write_png(image, o, a.threads); });
    if (!a.quiet)
        std::cout << a.out << ": " << image.width() << "x" << image.height() << ", "
                  << (a.close_up ? "corner close-up"
                                 : std::string(render::view_name(view)) + " view")
                  << ", " << r.surfaces.size() << " surfaces"
                  << (planes.empty() ? "" : " coloured by bound plane")
                  << (picture.scene.points.empty() ? "" : ", ")
                  << (picture.scene.points.empty()
                          ? ""
                          : std::to_string(picture.scene.points.size()) + " points")
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
    cmd->add_flag("--normals", a->normals,
                  "Draw every surface's normal as a short red line (by default only where the "
                  "disks are big enough on screen)");
    cmd->add_flag("--no-normals", a->no_normals, "Draw no normals");
    cmd->add_option("--color-by", a->color_by,
                    "auto: by bound plane when planes.json is there, else per surface; surface: "
                    "a colour per surface; plane: per bound plane (needs planes.json)")
        ->capture_default_str();
    cmd->add_option("--frame", a->frame,
                    "bulk: fit the structure (stray patches far from it may fall outside); all: "
                    "fit every surface")
        ->capture_default_str();
    cmd->add_flag("--close-up", a->close_up,
                  "A close-up of the corner where three bound planes meet, with normals (as the "
                  "paper's Fig. 6; replaces --view)");
    cmd->add_option("--size", a->size, "Picture size in pixels, WIDTHxHEIGHT")
        ->capture_default_str();
    add_threads_option(*cmd, a->threads, "Threads (0 = all cores); the picture is the same");
    cmd->add_flag("-q,--quiet", a->quiet, "No summary line on stdout");
    cmd->callback([a] { run_render(*a); });
}

}  // namespace surfgrow::cli
