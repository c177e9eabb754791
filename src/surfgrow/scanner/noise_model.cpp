#include "surfgrow/scanner/noise_model.hpp"

#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

namespace {

void require(bool ok, std::string_view what, double value) {
    if (!ok)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"noise model: ", what, ", got ", num(value)}));
}

}  // namespace

void NoiseModel::validate() const {
    require(std::isfinite(near_accuracy_mm) && near_accuracy_mm >= 0.0,
            "near accuracy must be >= 0 mm", near_accuracy_mm);
    require(std::isfinite(accuracy_knee_mm) && accuracy_knee_mm >= 0.0,
            "accuracy knee must be >= 0 mm", accuracy_knee_mm);
    require(std::isfinite(far_accuracy_fraction) && far_accuracy_fraction >= 0.0 &&
                far_accuracy_fraction <= 1.0,
            "far accuracy fraction must be in [0, 1]", far_accuracy_fraction);
    require(std::isfinite(coverage_factor) && coverage_factor > 0.0, "coverage factor must be > 0",
            coverage_factor);
    require(systematic_fraction >= 0.0 && systematic_fraction <= 1.0,
            "systematic fraction must be in [0, 1]", systematic_fraction);
    require(dropout_start_deg >= 0.0 && dropout_start_deg < dropout_full_deg,
            "dropout start must be >= 0 and below the full-dropout angle", dropout_start_deg);
    require(dropout_full_deg <= 90.0, "full-dropout angle must be <= 90 deg", dropout_full_deg);
    require(dropout_base_probability >= 0.0 && dropout_base_probability <= 1.0,
            "base dropout probability must be in [0, 1]", dropout_base_probability);
    require(beam_samples >= 1 && beam_samples <= 64, "beam samples must be in 1..64", beam_samples);
}

}  // namespace surfgrow::scanner
