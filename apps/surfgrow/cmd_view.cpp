// `surfgrow view OUT -o view.html`: an interactive 3D viewer of a result in one self-contained
// HTML file: the cloud, the disks, normals, bound planes and the coverage path (docs/viewer.md).
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "result_layers.hpp"
#include "surfaces_picture.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/render/group_colors.hpp"
#include "surfgrow/render/scene_builder.hpp"
#include "surfgrow/view/subsample.hpp"
#include "surfgrow/view/viewer_html.hpp"

namespace surfgrow::cli {

namespace {

struct ViewArgs {
    std::string dir;
    std::string out;
    std::string cloud;
    long long max_points = 2'000'000;
    bool quiet = false;
};

std::string grouped(std::uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

// The cloud layer: at most max_points points, coloured by surface as in the PNG, each with the
// index of its disk (`scene` holds the disks).
void add_cloud(view::ViewerScene& s, render::Scene& scene, const io::ResultFolder& folder,
               const std::string& file, std::size_t max_points) {
    const io::GrownCloud g = io::read_grown_cloud(file, folder);
    const std::vector<std::uint32_t> keep = view::choose_points(g.cloud, max_points);
    PointCloud shown;
    std::vector<std::int32_t> labels;
    shown.points.reserve(keep.size());
    for (const std::uint32_t i : keep) shown.points.push_back(g.cloud.points[i]);
    if (!g.labels.empty()) {
        labels.reserve(keep.size());
        for (const std::uint32_t i : keep) labels.push_back(g.labels[i]);
    }
    render::add_points(scene, shown, labels, folder.result.surfaces.size());
    s.points = std::move(scene.points);
    std::uint64_t finite = 0;
    for (const Vec3f& p : g.cloud.points) finite += is_finite(p) ? 1 : 0;
    if (keep.size() < finite)
        s.notes.push_back(cat({"Cloud: showing ", grouped(keep.size()), " of ", grouped(finite),
                               " points, the same ones every time (--max-points)"}));
    if (g.labels.empty()) s.notes.push_back("No labels (labels.bin): every point is grey");
}

void run_view(const ViewArgs& a) {
    if (a.max_points < 0)
        throw Error(
            ErrorCode::kInvalidParameter,
            cat({"--max-points must be 0 (no cloud) or more, got ", std::to_string(a.max_points)}));
    const io::ResultFolder folder = io::read_result_folder(a.dir);
    const io::StoredResult& r = folder.result;
    const ResultLayers layers = read_result_layers(folder.dir, r);

    view::ViewerScene s;
    const std::filesystem::path dir = std::filesystem::path(a.dir).lexically_normal();
    s.title = cat({"surfgrow: ", (dir.has_filename() ? dir : dir.parent_path()).string()});
    s.units = r.meta.units;
    s.legend =
        render::legend_line(r.stats.points_in, r.stats.surfaces, r.stats.registered_fraction());
    s.offset = r.meta.offset;
    s.back_faces = back_faces_for(r.stats.orientation);
    render::Scene scene = render::scene_from_surfaces(r.surfaces);
    if (layers.planes) {
        // The PNG's colours: faces that meet differ; each polygon in its disks' colour.
        const std::vector<std::int32_t> group = plane_of_surface(*layers.planes, r.surfaces.size());
        s.disk_plane_colors = render::group_colors(r.surfaces, group);
        s.planes.emplace();
        for (const PlaneOutline& p : *layers.planes) {
            render::Rgb color = render::kUnassignedGrey;
            for (const std::int32_t m : p.surfaces)
                if (m >= 0 && static_cast<std::size_t>(m) < group.size() && group[m] == p.id) {
                    color = s.disk_plane_colors[static_cast<std::size_t>(m)];
                    break;
                }
            s.planes->push_back({p.id, p.boundary, p.holes, color});
        }
    }
    if (layers.coverage) s.path = layers.coverage->goals;
    if (!a.cloud.empty() && a.max_points > 0)
        add_cloud(s, scene, folder, a.cloud, static_cast<std::size_t>(a.max_points));
    s.disks = std::move(scene.disks);

    std::uint64_t bytes = 0;
    io::write_atomically(a.out, [&](std::ostream& o) {
        const auto start = o.tellp();
        view::write_viewer_html(o, s);
        bytes = static_cast<std::uint64_t>(o.tellp() - start);
    });
    if (!a.quiet) {
        char size[32];
        std::snprintf(size, sizeof size, "%.1f MB", double(bytes) / 1e6);
        std::cout << a.out << ": " << size << ", " << r.surfaces.size() << " surfaces, "
                  << s.points.size() << " points" << (s.planes ? ", bound planes" : "")
                  << (s.path ? ", coverage path" : "") << std::endl;
    }
}

}  // namespace

void add_view_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "view", "Write an interactive 3D viewer of a result: one self-contained HTML file");
    auto a = std::make_shared<ViewArgs>();
    cmd->add_option("result", a->dir, "Result folder written by surfgrow grow")->required();
    cmd->add_option("-o,--out", a->out, "HTML file to write (replaced whole or not at all)")
        ->required();
    cmd->add_option("--cloud", a->cloud, "The cloud the result was grown from: the cloud layer");
    add_count_option(*cmd, "--max-points", a->max_points,
                     "At most this many cloud points in the page (a fixed subsample beyond; 0: "
                     "none)");
    cmd->add_flag("-q,--quiet", a->quiet, "No summary line on stdout");
    cmd->callback([a] { run_view(*a); });
}

}  // namespace surfgrow::cli
