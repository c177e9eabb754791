#include "surfgrow/planes/patch_members.hpp"

namespace surfgrow {

PatchMembers collect_patch_members(std::span<const Vec3f> points,
                                   std::span<const std::int32_t> labels, std::size_t surfaces) {
    PatchMembers m;
    m.offset.assign(surfaces + 1, 0);
    for (std::size_t i = 0; i < labels.size(); ++i)
        if (labels[i] >= 0 && is_finite(points[i]))
            ++m.offset[static_cast<std::size_t>(labels[i]) + 1];
    for (std::size_t s = 0; s < surfaces; ++s) m.offset[s + 1] += m.offset[s];
    m.index.resize(m.offset[surfaces]);
    m.point.resize(m.offset[surfaces]);
    std::vector<std::uint32_t> fill(m.offset.begin(), m.offset.end() - 1);
    for (std::size_t i = 0; i < labels.size(); ++i)
        if (labels[i] >= 0 && is_finite(points[i])) {
            const std::uint32_t k = fill[static_cast<std::size_t>(labels[i])]++;
            m.index[k] = static_cast<std::uint32_t>(i);
            m.point[k] = points[i];
        }
    return m;
}

}  // namespace surfgrow
