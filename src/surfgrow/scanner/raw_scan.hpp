// One tilting scan as the hardware gives it: n range readings per ray, and where it was taken.
#pragma once

#include <cstdint>
#include <span>
#include <string>
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

    // What a real acquisition records (surfgrow acquire); all optional, empty for a simulated scan.
    /// Empty, or one per tilt position: the angle the servo reported after it stopped, degrees.
    /// When present it, not spec.tilt's planned angle, places the position's rays.
    std::vector<double> tilt_read_deg;
    /// Empty, or one per tilt position: the sensor's time stamp (ms, 24 bits, wraps after 4.6 h)
    /// of the position's first reading.
    std::vector<std::uint32_t> sensor_time_ms;
    /// Positions the acquisition planned; 0, or spec.tilt.positions, for a whole scan. More than
    /// spec.tilt.positions marks a partial scan (it stopped early): kept, never fused silently.
    int planned_positions = 0;
    /// Who took it: the sensor's and servo's identity, the start time. Free text, at most
    /// kMaxRawScanNoteBytes.
    std::string note;
    /// Why a partial scan stopped ("URG: no good reply to GD... (time-out)"); empty otherwise.
    std::string stop_reason;

    [[nodiscard]] std::span<const std::uint16_t> ray_readings(std::size_t ray) const {
        const auto n = static_cast<std::size_t>(spec.readings_per_ray);
        return std::span<const std::uint16_t>(readings_mm).subspan(ray * n, n);
    }
    [[nodiscard]] bool has_truth() const { return !truth_face_id.empty(); }
    [[nodiscard]] bool partial() const { return planned_positions > spec.tilt.positions; }
    /// The tilt of position `i` in degrees: read back from the servo when recorded, else planned.
    [[nodiscard]] double tilt_deg(int i) const {
        return tilt_read_deg.empty() ? spec.tilt.tilt_deg(i)
                                     : tilt_read_deg[static_cast<std::size_t>(i)];
    }

    /// Throws Error(kInvalidParameter) if the spec is invalid, the pose is not rigid, the sizes
    /// of readings_mm / truth_face_id / tilt_read_deg / sensor_time_ms do not match the spec, a
    /// read-back angle is not finite or outside [-180, 180], planned_positions is negative or
    /// over 20000, or the note or stop reason is too long.
    void validate() const;
};

inline constexpr std::size_t kMaxRawScanNoteBytes = 65536;

}  // namespace surfgrow::scanner
