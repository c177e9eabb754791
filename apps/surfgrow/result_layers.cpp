#include "result_layers.hpp"

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/robot/coverage.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;

namespace {

std::optional<std::vector<PlaneOutline>> read_planes_layer(const fs::path& dir,
                                                           const io::StoredResult& result) {
    const fs::path file = dir / "planes.json";
    std::error_code ec;
    if (!fs::exists(file, ec)) return std::nullopt;
    const io::StoredPlanes stored = io::read_planes_json(file);
    io::check_derived_file(file, stored.meta, stored.planes.stats.patches, result,
                           "run `surfgrow planes` again");
    // Into the result's frame: file coordinates are the planes' frame plus their offset.
    const Vec3d shift = stored.meta.offset - result.meta.offset;
    std::vector<PlaneOutline> planes;
    for (std::size_t i = 0; i < stored.planes.planes.size(); ++i) {
        const surfgrow::BoundPlane& bp = stored.planes.planes[i];
        auto ring = [&](const Ring& r) {
            std::vector<Vec3d> out;
            out.reserve(r.size());
            for (const Vec2d& q : r) out.push_back(bp.to_world(q) + shift);
            return out;
        };
        // One entry per connected piece; the member surfaces go with the first.
        for (std::size_t k = 0; k < bp.polygons.size(); ++k) {
            const PolygonWithHoles& poly = bp.polygons[k];
            if (poly.outer.size() < 3) continue;
            PlaneOutline p;
            p.id = static_cast<std::int32_t>(i);
            p.normal = bp.normal;
            p.boundary = ring(poly.outer);
            for (const Ring& h : poly.holes)
                if (h.size() >= 3) p.holes.push_back(ring(h));
            if (k == 0)
                for (const std::uint32_t s : bp.patches)
                    p.surfaces.push_back(static_cast<std::int32_t>(s));
            planes.push_back(std::move(p));
        }
    }
    return planes;
}

std::optional<CoveragePath> read_coverage_layer(const fs::path& dir,
                                                const io::StoredResult& result) {
    const fs::path file = dir / "coverage.json";
    std::error_code ec;
    if (!fs::exists(file, ec)) return std::nullopt;
    const io::StoredCoverage stored = io::read_coverage_json(file);
    io::check_derived_file(file, stored.meta, std::nullopt, result,
                           "run `surfgrow coverage` again");
    const Vec3d shift = stored.meta.offset - result.meta.offset;
    CoveragePath path;
    path.goals.reserve(stored.plan.goals.size());
    for (const CoverageGoal& g : stored.plan.goals) path.goals.push_back(g.position + shift);
    return path;
}

}  // namespace

std::optional<std::vector<PlaneOutline>> read_plane_outlines(const fs::path& dir,
                                                             const io::StoredResult& result) {
    return read_planes_layer(dir, result);
}

ResultLayers read_result_layers(const fs::path& dir, const io::StoredResult& result) {
    ResultLayers layers;
    layers.planes = read_planes_layer(dir, result);
    layers.coverage = read_coverage_layer(dir, result);
    return layers;
}

std::vector<std::int32_t> plane_of_surface(const std::vector<PlaneOutline>& planes,
                                           std::size_t surface_count) {
    std::vector<std::int32_t> of(surface_count, -1);
    for (const PlaneOutline& p : planes)
        for (const std::int32_t s : p.surfaces)
            if (s >= 0 && static_cast<std::size_t>(s) < surface_count && of[s] < 0) of[s] = p.id;
    return of;
}

}  // namespace surfgrow::cli
