// Turning file coordinates into PointCloud points: the offset rule for large coordinates.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow::io {

/// Coordinates beyond this magnitude lose too much in a float (about 1 mm at 1e4) to be stored
/// without an offset, when the file holds more precision than a float.
inline constexpr double kOffsetThreshold = 1e4;

/// Coordinates beyond this are no place on (or in millimetres around) the Earth: sentinels such
/// as FLT_MAX that some writers use for missed returns. They never set the offset.
inline constexpr double kSentinelThreshold = 1e12;

/// The offset a point imposes: the point rounded to whole units when it is finite and its
/// largest coordinate magnitude is above kOffsetThreshold (and below kSentinelThreshold);
/// nullopt otherwise.
///
/// Readers use the first such point of the file (in file order), so the rule is the same for
/// every format and can be applied while streaming.
[[nodiscard]] inline std::optional<Vec3d> offset_for(double x, double y, double z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return std::nullopt;
    const double m = std::max({std::abs(x), std::abs(y), std::abs(z)});
    if (m <= kOffsetThreshold || m >= kSentinelThreshold) return std::nullopt;
    return Vec3d(std::round(x), std::round(y), std::round(z));
}

/// Appends points to a cloud one at a time (ASCII readers), applying the offset rule when the
/// source holds more precision than a float (`allow_offset`).
class PointBuilder {
  public:
    PointBuilder(PointCloud& cloud, bool allow_offset)
        : cloud_(cloud), allow_offset_(allow_offset) {}

    void add(double x, double y, double z) {
        if (allow_offset_ && !has_offset_) {
            if (const auto off = offset_for(x, y, z)) set_offset(*off);
        }
        const Vec3d& o = cloud_.offset;
        cloud_.points.emplace_back(static_cast<float>(x - o.x()), static_cast<float>(y - o.y()),
                                   static_cast<float>(z - o.z()));
    }

  private:
    // Points before the first large one were stored relative to zero: move them too.
    void set_offset(const Vec3d& offset) {
        has_offset_ = true;
        cloud_.offset = offset;
        for (Vec3f& p : cloud_.points) p = (p.cast<double>() - offset).cast<float>();
    }

    PointCloud& cloud_;
    bool allow_offset_;
    bool has_offset_ = false;
};

/// A label value read as a number: integers of int32 or uint32 range are kept (uint32 values
/// above INT32_MAX wrap to negative, so 0xFFFFFFFF reads as -1); false for anything else.
[[nodiscard]] inline bool label_from_double(double v, int32_t& out) {
    if (!(v >= -2147483648.0 && v <= 4294967295.0) || v != std::floor(v)) return false;
    out = static_cast<int32_t>(static_cast<uint32_t>(static_cast<int64_t>(v)));
    return true;
}

}  // namespace surfgrow::io
