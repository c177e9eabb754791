#include "surfgrow/scanner/tilting_scanner.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

TiltingScanner::TiltingScanner(ScannerSpec spec) : TiltingScanner(std::move(spec), {}) {}

TiltingScanner::TiltingScanner(ScannerSpec spec, std::span<const double> tilt_deg)
    : spec_(std::move(spec)) {
    spec_.validate();
    if (!tilt_deg.empty() && tilt_deg.size() != static_cast<std::size_t>(tilt_count()))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({std::to_string(tilt_deg.size()), " tilt angles for ",
                         std::to_string(tilt_count()), " tilt positions"}));
    tilt_deg_.resize(static_cast<std::size_t>(tilt_count()));
    for (int i = 0; i < tilt_count(); ++i)
        tilt_deg_[static_cast<std::size_t>(i)] =
            tilt_deg.empty() ? spec_.tilt.tilt_deg(i) : tilt_deg[static_cast<std::size_t>(i)];
    tilt_rot_.reserve(static_cast<std::size_t>(tilt_count()));
    for (int i = 0; i < tilt_count(); ++i) {
        const double t = tilt_rad(i);
        Mat3d r;
        // Ry(-t): a positive tilt turns x toward +z.
        r << std::cos(t), 0.0, -std::sin(t), 0.0, 1.0, 0.0, std::sin(t), 0.0, std::cos(t);
        tilt_rot_.push_back(r);
    }
    pan_cos_.resize(static_cast<std::size_t>(step_count()));
    pan_sin_.resize(static_cast<std::size_t>(step_count()));
    for (int j = 0; j < step_count(); ++j) {
        pan_cos_[j] = std::cos(pan_rad(j));
        pan_sin_[j] = std::sin(pan_rad(j));
    }
}

double TiltingScanner::tilt_rad(int tilt) const {
    return deg_to_rad(tilt_deg_[static_cast<std::size_t>(tilt)]);
}

double TiltingScanner::pan_rad(int step) const {
    return deg_to_rad(spec_.laser.pan_deg(step));
}

Vec3d TiltingScanner::optical_centre(int tilt) const {
    return tilt_rot_[tilt] * spec_.optical_offset_m;
}

Ray TiltingScanner::ray(int tilt, int step) const {
    const Mat3d& r = tilt_rot_[tilt];
    return {r * spec_.optical_offset_m, r * beam_in_laser(step)};
}

Vec3d TiltingScanner::to_sensor(int tilt, int step, double range_m) const {
    return tilt_rot_[tilt] * (spec_.optical_offset_m + range_m * beam_in_laser(step));
}

}  // namespace surfgrow::scanner
