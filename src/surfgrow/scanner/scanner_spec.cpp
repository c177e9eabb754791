#include "surfgrow/scanner/scanner_spec.hpp"

#include <cmath>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

namespace {

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorCode::kInvalidParameter, message);
}

std::string inum(long v) {
    return std::to_string(v);
}

}  // namespace

void LaserSpec::validate() const {
    if (!(std::isfinite(step_deg) && step_deg > 0.0 && step_deg <= 90.0))
        invalid(cat({"laser step angle must be in (0, 90] deg, got ", num(step_deg)}));
    if (first_step < 0 || last_step < first_step || last_step - first_step >= 8192)
        invalid(cat({"laser steps must satisfy 0 <= first <= last < first + 8192, got ",
                     inum(first_step), "..", inum(last_step)}));
    if (first_detect_step < first_step || last_detect_step > last_step ||
        last_detect_step < first_detect_step)
        invalid(
            cat({"laser detection steps ", inum(first_detect_step), "..", inum(last_detect_step),
                 " must lie inside the sweep ", inum(first_step), "..", inum(last_step)}));
    // In double: front_step is any int in a file (a raw scan's header), and int - int overflows.
    const double lo = (static_cast<double>(first_step) - front_step) * step_deg;
    const double hi = (static_cast<double>(last_step) - front_step) * step_deg;
    if (lo < -180.0 || hi > 180.0)
        invalid(cat({"laser sweep must lie within -180..180 deg, got ", num(lo), "..", num(hi)}));
    if (min_range_mm < 1 || max_range_mm <= min_range_mm || max_range_mm == 65535)
        invalid(cat({"laser range limits must satisfy 1 <= min < max < 65535 mm, got ",
                     inum(min_range_mm), "..", inum(max_range_mm)}));
    if (!(std::isfinite(beam_divergence_deg) && beam_divergence_deg >= 0.0 &&
          beam_divergence_deg <= 10.0))
        invalid(
            cat({"laser beam divergence must be in [0, 10] deg, got ", num(beam_divergence_deg)}));
}

void TiltSpec::validate() const {
    if (!(std::isfinite(first_deg) && std::isfinite(step_deg) && step_deg > 0.0))
        invalid(cat({"tilt first angle and step must be finite with step > 0, got ", num(first_deg),
                     " and ", num(step_deg)}));
    if (positions < 1 || positions > 20000)
        invalid(cat({"tilt positions must be in 1..20000, got ", inum(positions)}));
    if (first_deg < -180.0 || last_deg() > 180.0)
        invalid(cat({"tilt angles must lie within -180..180 deg, got ", num(first_deg), "..",
                     num(last_deg())}));
}

void ScannerSpec::validate() const {
    laser.validate();
    tilt.validate();
    if (!optical_offset_m.allFinite() || optical_offset_m.norm() > 1.0)
        invalid(cat({"optical offset must be finite and under 1 m, got ",
                     num(optical_offset_m.norm()), " m"}));
    if (readings_per_ray < 1 || readings_per_ray > 255)
        invalid(cat({"readings per ray (n) must be in 1..255, got ", inum(readings_per_ray)}));
    if (readings() > kMaxReadingsPerScan)
        invalid(cat({"a scan of ", inum(static_cast<long>(readings())),
                     " readings is too large (at most 2^28)"}));
}

LaserSpec urg04lx_paper() {
    return LaserSpec{};
}

LaserSpec urg04lx_scip_682() {
    LaserSpec s;
    s.step_deg = 360.0 / 1024.0;
    s.first_step = 44;
    s.last_step = 725;
    s.front_step = 384;
    s.first_detect_step = 44;
    s.last_detect_step = 725;
    s.beam_divergence_deg = 360.0 / 1024.0;
    return s;
}

LaserSpec urg04lx_scip_769() {
    LaserSpec s = urg04lx_scip_682();
    s.first_step = 0;
    s.last_step = 768;
    return s;
}

std::vector<std::string> laser_preset_names() {
    return {"urg04lx-paper", "urg04lx-682", "urg04lx-769"};
}

LaserSpec laser_preset(std::string_view name) {
    if (name == "urg04lx-paper") return urg04lx_paper();
    if (name == "urg04lx-682") return urg04lx_scip_682();
    if (name == "urg04lx-769") return urg04lx_scip_769();
    invalid(cat(
        {"unknown laser preset '", name, "' (known: urg04lx-paper, urg04lx-682, urg04lx-769)"}));
}

}  // namespace surfgrow::scanner
