#include "surfgrow/core/grown_points.hpp"

namespace surfgrow {

Vec3d crop_centre(const CloudView& cloud, const GrowerConfig& config) {
    if (config.crop.center) return *config.crop.center;
    if (config.viewpoint) return *config.viewpoint;
    if (cloud.viewpoint) return *cloud.viewpoint;
    return Vec3d(-cloud.offset);
}

WorkspaceMask workspace_mask(const CloudView& cloud, const GrowerConfig& config) {
    WorkspaceMask mask;
    const WorkspaceCrop& crop = config.crop;
    if (!crop.active()) return mask;
    const Vec3d centre = crop_centre(cloud, config);
    const double r2 = crop.radius ? *crop.radius * *crop.radius : 0.0;
    mask.inside.assign(cloud.size(), 0);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Vec3f& pf = cloud.points[i];
        if (!is_finite(pf)) continue;
        const Vec3d p = pf.cast<double>();
        const bool inside = (!crop.box || crop.box->contains(p)) &&
                            (!crop.radius || (p - centre).squaredNorm() <= r2);
        if (inside)
            mask.inside[i] = 1;
        else
            ++mask.cropped;
    }
    return mask;
}

std::vector<std::uint8_t> grown_point_mask(const CloudView& cloud, const GrowerConfig& config) {
    WorkspaceMask mask = workspace_mask(cloud, config);
    if (config.crop.active()) return std::move(mask.inside);
    std::vector<std::uint8_t> finite(cloud.size(), 0);
    for (std::size_t i = 0; i < cloud.size(); ++i) finite[i] = is_finite(cloud.points[i]) ? 1 : 0;
    return finite;
}

}  // namespace surfgrow
