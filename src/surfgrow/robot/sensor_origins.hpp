// Where each point was seen from: the start of the ray that carves free space up to it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/grower_config.hpp"

namespace surfgrow {

/// The sensor origin of every point, when known.
///
/// Unlike normal orientation, this never guesses (no frame-origin or +z fallback): a wrong origin
/// would carve free space through real obstacles, which a planner would then trust.
struct SensorOrigins {
    enum class Source : std::uint8_t {
        kNone,         ///< unknown: no carving
        kScanOrigins,  ///< each point's own scan origin (fused clouds)
        kViewpoint,    ///< one origin for every point
    };
    Source source = Source::kNone;
    std::vector<Vec3d> origins;  ///< one per scan (kScanOrigins) or one (kViewpoint)

    [[nodiscard]] bool known() const { return source != Source::kNone; }

    /// Origin of point i of `cloud` (the cloud these origins were taken from), or nullptr.
    [[nodiscard]] const Vec3d* origin_of(const CloudView& cloud, std::size_t i) const {
        if (source == Source::kViewpoint) return &origins.front();
        if (source == Source::kScanOrigins && i < cloud.scan_index.size()) {
            const std::uint32_t s = cloud.scan_index.data()[i];
            return s < origins.size() ? origins.data() + s : nullptr;
        }
        return nullptr;
    }
};

[[nodiscard]] inline const char* sensor_origins_name(SensorOrigins::Source s) {
    switch (s) {
        case SensorOrigins::Source::kScanOrigins:
            return "scan_origins";
        case SensorOrigins::Source::kViewpoint:
            return "viewpoint";
        case SensorOrigins::Source::kNone:
            return "none";
    }
    return "none";
}

/// The cloud's per-scan origins (scan_index and scan_origins), else config.viewpoint, else the
/// cloud's viewpoint, else none. Origins that are not finite are dropped.
[[nodiscard]] inline SensorOrigins sensor_origins(const CloudView& cloud,
                                                  const GrowerConfig& config) {
    SensorOrigins s;
    if (cloud.has_scan_index() && !cloud.scan_origins.empty()) {
        bool finite = true;
        for (const Vec3d& o : cloud.scan_origins) finite = finite && o.allFinite();
        if (finite) {
            s.source = SensorOrigins::Source::kScanOrigins;
            s.origins.assign(cloud.scan_origins.begin(), cloud.scan_origins.end());
            return s;
        }
    }
    const std::optional<Vec3d>& v = config.viewpoint ? config.viewpoint : cloud.viewpoint;
    if (v && v->allFinite()) {
        s.source = SensorOrigins::Source::kViewpoint;
        s.origins = {*v};
    }
    return s;
}

}  // namespace surfgrow
