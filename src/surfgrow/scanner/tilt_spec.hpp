// The tilt servo that sweeps the laser's scan plane (the paper's digital servo, Fig. 1c).
#pragma once

namespace surfgrow::scanner {

/// Tilt positions first_deg + i * step_deg for i in [0, positions). Positive tilt raises the
/// laser's forward axis (+x toward +z); see TiltingScanner for the frames.
///
/// The paper's values: -60 deg upward in 1/3 deg steps, 360 positions (so the last position is
/// +59.67 deg; 361 would be needed to reach +60 exactly, but the paper counts 360).
struct TiltSpec {
    double first_deg = -60.0;     ///< tilt of the first position, degrees
    double step_deg = 1.0 / 3.0;  ///< increment between positions, degrees (> 0)
    int positions = 360;          ///< number of tilt positions in a scan

    [[nodiscard]] double tilt_deg(int index) const { return first_deg + index * step_deg; }
    [[nodiscard]] double last_deg() const { return tilt_deg(positions - 1); }

    /// Throws Error(kInvalidParameter) unless step > 0, 1 <= positions <= 20000 and every tilt
    /// lies within [-180, 180] deg.
    void validate() const;

    friend bool operator==(const TiltSpec&, const TiltSpec&) = default;
};

}  // namespace surfgrow::scanner
