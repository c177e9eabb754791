// One tilting scan as the hardware gives it: n range readings per ray, and where it was taken.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/scanner/pose.hpp"
#include "surfgrow/scanner/scanner_spec.hpp"

namespace surfgrow::scanner {

/// Readings are whole millimetres as the URG reports them; 0 means no return. Values outside the
/// laser's [min_range_mm, max_range_mm] are kept as read (the URG's error codes are 1..19) and
/// left out by the range filter.
struct RawScan {
    ScannerSpec spec = {};
    Pose pose = Pose::Identity();  ///< sensor frame to world
    /// spec.readings() values, ray-major: readings_mm[ray * n + k] for ray = tilt * steps + step.
    std::vector<std::uint16_t> readings_mm;
    /// Optional ground truth (simulated scans): empty, or one face id per ray, -1 where the beam
    /// met no surface or more than one face (a mixed pixel, an edge).
    std::vector<std::int32_t> truth_face_id;

    [[nodiscard]] std::span<const std::uint16_t> ray_readings(std::size_t ray) const {
        const auto n = static_cast<std::size_t>(spec.readings_per_ray);
        return std::span<const std::uint16_t>(readings_mm).subspan(ray * n, n);
    }
    [[nodiscard]] bool has_truth() const { return !truth_face_id.empty(); }

    /// Throws Error(kInvalidParameter) if the spec is invalid, the pose is not rigid, or the
    /// sizes of readings_mm / truth_face_id do not match the spec.
    void validate() const;
};

}  // namespace surfgrow::scanner
