#include "surfgrow/scanner/veil_filter.hpp"

#include <cmath>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow::scanner {

void validate(const VeilFilter& f) {
    if (!(f.angle_deg >= 0 && f.angle_deg <= 45))
        throw Error(
            ErrorCode::kInvalidParameter,
            cat({"mixed-pixel angle must lie within 0..45 degrees, got ", num(f.angle_deg)}));
    if (!(f.min_step_mm >= 0) || !std::isfinite(f.min_step_mm))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"mixed-pixel step must be >= 0 mm, got ", num(f.min_step_mm)}));
}

std::vector<std::uint8_t> veil_rays(const TiltingScanner& scanner, std::span<const double> range_mm,
                                    const VeilFilter& filter) {
    validate(filter);
    const std::size_t rays = scanner.ray_count();
    if (range_mm.size() != rays)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"mixed-pixel filter: ", std::to_string(range_mm.size()), " ranges for ",
                         std::to_string(rays), " rays"}));
    std::vector<std::uint8_t> veil(rays, 0);
    if (filter.angle_deg == 0) return veil;
    const int tilts = scanner.tilt_count(), steps = scanner.step_count();
    const double cos_max = std::cos(filter.angle_deg * M_PI / 180);
    // The sensor-frame points, each once (the filter needs no pose: angles and ranges only).
    std::vector<Vec3d> at(rays, Vec3d::Constant(NAN));
#pragma omp parallel for schedule(static) num_threads(resolve_threads(0))
    for (int t = 0; t < tilts; ++t)
        for (int s = 0; s < steps; ++s) {
            const std::size_t r = scanner.ray_index(t, s);
            if (!std::isnan(range_mm[r])) at[r] = scanner.to_sensor(t, s, range_mm[r] * 1e-3);
        }
    // Whether neighbour (t, s) lies along `back` (unit, from the point to its optical centre)
    // beyond the step floor: +1 nearer the sensor, -1 farther, 0 neither or no neighbour.
    const auto along = [&](std::size_t r, const Vec3d& back, int t, int s) {
        if (t < 0 || t >= tilts || s < 0 || s >= steps) return 0;
        const std::size_t q = scanner.ray_index(t, s);
        if (std::isnan(range_mm[q]) || std::abs(range_mm[q] - range_mm[r]) <= filter.min_step_mm)
            return 0;
        const double c = back.dot((at[q] - at[r]).normalized());
        return c > cos_max ? 1 : (c < -cos_max ? -1 : 0);
    };
#pragma omp parallel for schedule(static) num_threads(resolve_threads(0))
    for (int t = 0; t < tilts; ++t) {
        const Vec3d centre = scanner.optical_centre(t);
        for (int s = 0; s < steps; ++s) {
            const std::size_t r = scanner.ray_index(t, s);
            if (std::isnan(range_mm[r])) continue;
            const Vec3d back = (centre - at[r]).normalized();
            veil[r] = along(r, back, t, s - 1) * along(r, back, t, s + 1) < 0 ||
                      along(r, back, t - 1, s) * along(r, back, t + 1, s) < 0;
        }
    }
    return veil;
}

}  // namespace surfgrow::scanner
