#include "surfgrow/render/scene_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/render/group_colors.hpp"

namespace surfgrow::render {

Scene scene_from_surfaces(const std::vector<Surface>& surfaces, const SurfaceStyle& style) {
    if (!style.groups.empty() && style.groups.size() != surfaces.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"surface groups must be one per surface: got ",
                         std::to_string(style.groups.size()), " for ",
                         std::to_string(surfaces.size()), " surfaces"}));
    if (!(style.normal_length >= 0) || !std::isfinite(style.normal_length))
        throw Error(
            ErrorCode::kInvalidParameter,
            cat({"normal length must be zero or positive, got ", num(style.normal_length)}));
    std::vector<Rgb> colors;
    if (!style.groups.empty()) colors = group_colors(surfaces, style.groups);
    Scene scene;
    scene.disks.reserve(surfaces.size());
    if (style.normals) scene.lines.reserve(surfaces.size());
    std::vector<double> radii;
    radii.reserve(surfaces.size());
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const Surface& s = surfaces[i];
        const double len = s.normal.norm();
        const Vec3d n = len > 0 ? Vec3d(s.normal / len) : Vec3d::UnitZ();
        // The home point may sit off the fitted plane by up to the tolerance: project it in.
        const Vec3d center = s.home - n * n.dot(s.home - s.centroid);
        const bool usable = len > 0 && std::isfinite(len) && s.radius > 0 &&
                            std::isfinite(s.radius) && center.allFinite();
        scene.disks.push_back(
            {center, n, usable ? s.radius : 0.0,
             colors.empty() ? id_color(static_cast<std::int64_t>(i)) : colors[i]});
        if (!usable) continue;
        radii.push_back(s.radius);
        if (style.normals) {
            const double l = style.normal_length > 0 ? style.normal_length : s.radius;
            scene.lines.push_back(
                {center, center + l * n, style.normal_color, static_cast<std::int32_t>(i)});
        }
    }
    if (!radii.empty()) {
        auto mid = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
        std::nth_element(radii.begin(), mid, radii.end());
        scene.point_depth_bias = *mid;
    }
    return scene;
}

void add_points(Scene& scene, const CloudView& cloud, std::span<const std::int32_t> labels,
                std::size_t surface_count, const SurfaceStyle& style) {
    if (!labels.empty() && labels.size() != cloud.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"point labels must be one per point: got ", std::to_string(labels.size()),
                         " for ", std::to_string(cloud.size()), " points"}));
    scene.points.reserve(scene.points.size() + cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Vec3f& p = cloud.points[i];
        if (!is_finite(p)) continue;
        Rgb c = kUnassignedGrey;
        std::int32_t disk = -1;
        if (!labels.empty() && labels[i] >= 0) {
            const auto label = static_cast<std::size_t>(labels[i]);
            const bool known = label < surface_count;
            const bool has_disk = known && label < scene.disks.size();
            c = scaled(has_disk ? scene.disks[label].color : id_color(labels[i]),
                       style.point_shade);
            if (has_disk) disk = labels[i];
        }
        scene.points.push_back({p, c, disk});
    }
}

std::string legend_line(std::uint64_t points, std::uint64_t surfaces, double registered_fraction) {
    char percent[32];
    std::snprintf(percent, sizeof percent, "%.1f%%", 100.0 * registered_fraction);
    return cat({std::to_string(points), " points -> ", std::to_string(surfaces), " surfaces, ",
                percent, " registered"});
}

}  // namespace surfgrow::render
