#include "planes_options.hpp"

#include <cstdio>

#include "cli_common.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/planes/plane_mesh.hpp"

namespace surfgrow::cli {

void PlanesOptions::add_to(CLI::App& cmd) {
    cmd.add_option("--angle", angle, "Merge patches whose normals differ by at most this, degrees")
        ->capture_default_str();
    cmd.add_option("--offset", offset,
                   "... and whose centroids lie within this of the other plane, with unit "
                   "(default: 3 x measured noise, within mu/4..mu/2)");
    cmd.add_option("--adjacency", adjacency,
                   "Patches are neighbours when member points lie this close (default: mu/2)");
    cmd.add_option("--max-gap", max_gap,
                   "Coplanar regions this close are one face (default: 5 mu)");
    cmd.add_flag("--no-gap-bridging", no_bridge, "Never merge regions across gaps");
    cmd.add_option("--resolution", resolution, "Boundary raster cell, with unit (default: mu/2)");
    cmd.add_option("--closing", closing,
                   "Close boundary gaps narrower than about twice this (default: from the point "
                   "spacing)");
    cmd.add_option("--simplify", simplify,
                   "Douglas-Peucker tolerance of the polygons (default: the resolution)");
    cmd.add_flag("--obj", obj, "Also write planes.obj");
}

BoundPlaneConfig PlanesOptions::config(double metres, double mu, int threads) const {
    auto len = [&](const std::string& text, const char* option) {
        return text.empty() ? 0.0 : parse_length_m(text, option) / metres;
    };
    BoundPlaneConfig c;
    c.mu = mu;
    c.max_angle_deg = angle;
    c.max_offset = len(offset, "--offset");
    c.adjacency = len(adjacency, "--adjacency");
    c.max_gap = no_bridge ? -1.0 : len(max_gap, "--max-gap");
    c.resolution = len(resolution, "--resolution");
    c.closing_radius = len(closing, "--closing");
    c.simplify_tolerance = len(simplify, "--simplify");
    c.threads = threads;
    // A length given explicitly must be positive: 0 would silently mean "default".
    const std::pair<const std::string*, double> given[] = {{&offset, c.max_offset},
                                                           {&adjacency, c.adjacency},
                                                           {&resolution, c.resolution},
                                                           {&closing, c.closing_radius},
                                                           {&simplify, c.simplify_tolerance}};
    for (const auto& [text, v] : given)
        if (!text->empty() && !(v > 0))
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"'", *text, "': lengths must be positive"}));
    if (!max_gap.empty() && !(c.max_gap > 0))
        throw Error(ErrorCode::kInvalidParameter,
                    "--max-gap must be positive (--no-gap-bridging turns bridging off)");
    validate(c);
    return c;
}

std::string planes_summary(const BoundPlanes& planes, const std::string& units) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%llu surfaces -> %zu planes, %.4g %s2",
                  static_cast<unsigned long long>(planes.stats.patches), planes.planes.size(),
                  planes.stats.area, units.c_str());
    std::string line = buf;
    if (planes.stats.degenerate) {
        std::snprintf(buf, sizeof buf, " (%llu degenerate)",
                      static_cast<unsigned long long>(planes.stats.degenerate));
        line += buf;
    }
    return line;
}

}  // namespace surfgrow::cli
