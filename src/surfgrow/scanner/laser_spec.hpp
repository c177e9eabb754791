// The 2D laser range finder on the tilt servo: angular layout, range limits, beam (URG-04LX).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace surfgrow::scanner {

/// Angular layout and range limits of a 2D laser scanner, in the device's own step numbering.
///
/// Step s points at pan angle (s - front_step) * step_deg, counter-clockwise seen from above the
/// laser (from its +x toward its +y). A sweep reports steps first_step..last_step; only steps
/// first_detect_step..last_detect_step can return a range, the others lie in the blind sector
/// behind the device (as on the URG-04LX, whose SCIP sweep covers 270 deg around a 240 deg fan).
struct LaserSpec {
    double step_deg = 0.36;             ///< angle between adjacent steps, degrees
    int first_step = 0;                 ///< first step reported in a sweep
    int last_step = 767;                ///< last step reported (inclusive)
    int front_step = 384;               ///< step pointing straight ahead (laser +x)
    int first_detect_step = 51;         ///< first step that can return a range
    int last_detect_step = 717;         ///< last step that can return a range (inclusive)
    std::uint16_t min_range_mm = 20;    ///< shortest range the device reports
    std::uint16_t max_range_mm = 4000;  ///< longest range the device reports
    double beam_divergence_deg = 0.36;  ///< full cone angle of the beam (mixed pixels)

    /// Number of readings in one sweep (the rays per tilt position).
    [[nodiscard]] int steps() const { return last_step - first_step + 1; }
    /// Pan angle in degrees of the step `first_step + index`.
    [[nodiscard]] double pan_deg(int index) const {
        return (first_step + index - front_step) * step_deg;
    }
    /// Whether the step `first_step + index` lies in the detection fan.
    [[nodiscard]] bool can_detect(int index) const {
        const int s = first_step + index;
        return s >= first_detect_step && s <= last_detect_step;
    }

    /// Throws Error(kInvalidParameter) naming the first value out of its valid range.
    void validate() const;

    friend bool operator==(const LaserSpec&, const LaserSpec&) = default;
};

/// The paper's layout: up to 768 readings per sweep at 0.36 deg, 20..4000 mm. The 240 deg fan
/// (steps 51..717, +-119.88 deg, 667 rays) sits inside the 768-step sweep the way the real
/// device's fan sits inside its SCIP sweep; the paper's "768 points" counts the whole sweep.
[[nodiscard]] LaserSpec urg04lx_paper();
/// The real URG-04LX (SCIP 2.0: ARES 1024 steps per turn, AFRT 384), steps 44..725: the 682
/// readings of the detection fan only. Range limited to the paper's 4000 mm (SCIP DMAX is 5600).
[[nodiscard]] LaserSpec urg04lx_scip_682();
/// The real URG-04LX's full SCIP sweep, steps 0..768 (769 readings); steps outside 44..725 never
/// return a range. Range limited to the paper's 4000 mm (SCIP DMAX is 5600).
[[nodiscard]] LaserSpec urg04lx_scip_769();

/// Names accepted by laser_preset(): "urg04lx-paper", "urg04lx-682", "urg04lx-769".
[[nodiscard]] std::vector<std::string> laser_preset_names();
/// The preset called `name`; throws Error(kInvalidParameter) listing the names otherwise.
[[nodiscard]] LaserSpec laser_preset(std::string_view name);

}  // namespace surfgrow::scanner
