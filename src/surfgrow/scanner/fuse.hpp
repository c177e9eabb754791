// From raw scans to one point cloud: filter each ray (eq. 1), convert, fuse several poses.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/scanner/raw_scan.hpp"
#include "surfgrow/scanner/veil_filter.hpp"

namespace surfgrow::scanner {

struct FuseOptions {
    int trim_q = 1;                  ///< q of eq. (1): readings dropped from each end
    std::uint16_t min_range_mm = 0;  ///< 0: each scan's laser limit; else within it, mm
    std::uint16_t max_range_mm = 0;  ///< 0: each scan's laser limit; else within it, mm
    /// A partial scan (RawScan::partial: the acquisition stopped early) is refused unless set.
    bool allow_partial = false;
    /// Mixed pixels in the depth gaps behind silhouettes dropped (veil_filter.hpp); off by
    /// default (angle 0: every ray kept).
    VeilFilter veil;
};

/// What fuse_scans left out, scan by scan.
struct FuseReport {
    std::vector<std::uint64_t> veil_points;  ///< mixed pixels dropped (FuseOptions::veil)
};

/// Fuses scans taken at known poses into one cloud, in metres, world frame.
///
/// Each ray's readings go through RangeFilter (eq. 1); a ray with a range that is not a mixed
/// pixel (options.veil; counted in `report` if given) becomes the point
/// pose * TiltingScanner::to_sensor(tilt, step, range), at the servo's read-back angle where the
/// scan recorded one. Points are ordered scan by scan, ray by
/// ray. For every point scan_index holds its scan's position in `scans`; scan_origins[k] is scan
/// k's sensor origin (its pose's translation) so normals can be turned toward the sensor. With a
/// single scan, viewpoint is that origin too. When every scan carries ground truth, labels holds
/// each point's true face id (-1 for none or a mixed pixel); otherwise labels stays empty.
///
/// Throws Error(kInvalidParameter) naming the scan if a scan is invalid, n <= 2q, or a range
/// limit lies outside the scan's laser limits (or min >= max), or a scan is partial and
/// options.allow_partial is not set.
[[nodiscard]] PointCloud fuse_scans(std::span<const RawScan> scans, const FuseOptions& options = {},
                                    FuseReport* report = nullptr);

}  // namespace surfgrow::scanner
