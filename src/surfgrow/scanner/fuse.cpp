#include "surfgrow/scanner/fuse.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/scanner/range_filter.hpp"
#include "surfgrow/scanner/tilting_scanner.hpp"

namespace surfgrow::scanner {

namespace {

// Prefixes an Error's message with the scan it concerns, keeping its code.
template <class F>
auto for_scan(std::size_t k, F&& f) {
    try {
        return f();
    } catch (const Error& e) {
        throw Error(e.code(), cat({"scan ", std::to_string(k), ": ", e.what()}));
    }
}

RangeFilter make_filter(const RawScan& scan, const FuseOptions& o) {
    const LaserSpec& laser = scan.spec.laser;
    const std::uint16_t lo = o.min_range_mm == 0 ? laser.min_range_mm : o.min_range_mm;
    const std::uint16_t hi = o.max_range_mm == 0 ? laser.max_range_mm : o.max_range_mm;
    if (lo < laser.min_range_mm || hi > laser.max_range_mm || lo >= hi)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"range limits ", std::to_string(lo), "..", std::to_string(hi),
                         " mm must be increasing and lie within the sensor's limits ",
                         std::to_string(laser.min_range_mm), "..",
                         std::to_string(laser.max_range_mm), " mm"}));
    return RangeFilter(scan.spec.readings_per_ray, o.trim_q, lo, hi);
}

}  // namespace

PointCloud fuse_scans(std::span<const RawScan> scans, const FuseOptions& options,
                      FuseReport* report) {
    validate(options.veil);
    PointCloud cloud;
    if (report) report->veil_points.assign(scans.size(), 0);
    bool all_truth = !scans.empty();
    for (const RawScan& s : scans) all_truth = all_truth && s.has_truth();

    for (std::size_t k = 0; k < scans.size(); ++k) {
        const RawScan& scan = scans[k];
        for_scan(k, [&] {
            scan.validate();
            return 0;
        });
        const RangeFilter filter = for_scan(k, [&] { return make_filter(scan, options); });
        if (scan.partial() && !options.allow_partial)
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"scan ", std::to_string(k),
                             " is partial: ", std::to_string(scan.spec.tilt.positions), " of ",
                             std::to_string(scan.planned_positions),
                             " tilt positions (the acquisition stopped early",
                             scan.stop_reason.empty() ? "" : ": ", scan.stop_reason,
                             "); allow partial scans to use it"}));
        const TiltingScanner scanner(scan.spec, scan.tilt_read_deg);
        const std::size_t rays = scan.spec.rays();
        std::vector<double> range_mm(rays);
#pragma omp parallel for schedule(static) num_threads(resolve_threads(0))
        for (std::size_t r = 0; r < rays; ++r) range_mm[r] = filter(scan.ray_readings(r));

        const std::vector<std::uint8_t> veil = veil_rays(scanner, range_mm, options.veil);
        const int steps = scanner.step_count();
        for (std::size_t r = 0; r < rays; ++r) {
            if (std::isnan(range_mm[r])) continue;
            if (veil[r]) {
                if (report) ++report->veil_points[k];
                continue;
            }
            const int tilt = static_cast<int>(r / static_cast<std::size_t>(steps));
            const int step = static_cast<int>(r % static_cast<std::size_t>(steps));
            cloud.points.push_back(
                scanner.to_world(scan.pose, tilt, step, range_mm[r] * 1e-3).cast<float>());
            cloud.scan_index.push_back(static_cast<std::uint32_t>(k));
            if (all_truth) cloud.labels.push_back(scan.truth_face_id[r]);
        }
        cloud.scan_origins.push_back(scan.pose.translation());
    }
    if (scans.size() == 1) cloud.viewpoint = cloud.scan_origins.front();
    return cloud;
}

}  // namespace surfgrow::scanner
