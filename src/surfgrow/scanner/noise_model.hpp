// The URG-04LX's range errors, dropouts and mixed pixels, from its datasheet (docs/scanner.md).
#pragma once

#include <cmath>
#include <cstdint>

#include "surfgrow/core/random.hpp"

namespace surfgrow::scanner {

/// How a simulated reading departs from the true range.
///
/// Range noise. The datasheet's accuracy is +-10 mm up to 1 m and +-1 % of the range beyond. A
/// Gaussian has no bound, so "+-" is read as the 95 % interval, i.e. 2 sigma (coverage factor
/// k = 2, the GUM's usual expanded uncertainty): sigma(r) = max(10 mm, 1 % r) / 2, so 5 mm up to
/// 1 m and 15 mm at 3 m. One sigma would put a third of all readings outside the datasheet's
/// bound (a sensor out of spec); three sigma would treat the bound as a hard limit (softer).
///
/// Part of that error is systematic: a datasheet accuracy covers the bias that depends on the
/// target (colour, material) and on drift, which repeated readings cannot average away. A share
/// `systematic_fraction` of sigma^2 is therefore drawn once per scan and face of the scene -- an
/// offset of that surface in that scan, scaled by sigma(r) -- and the rest per reading. Each
/// single reading still has sigma(r) in all; eq. (1) averages away only the per-reading part, and
/// the offsets shift whole surfaces (a little differently in each scan) instead of roughening them.
///
/// Dropouts. A reading is lost (0 = no return) with probability dropout_probability(incidence):
/// 0 up to dropout_start_deg, a smoothstep up to 1 at dropout_full_deg (a weak, glancing return
/// from painted steel), plus dropout_base_probability everywhere. Beyond the laser's range limits
/// there is no return at all.
///
/// Mixed pixels. The beam is a cone of the laser's beam divergence; beam_samples sub-rays sample
/// it (centre + a ring). Their ranges are blended weighted by returned power cos(incidence) / r^2,
/// the small-phase limit of the phase-shift sensor's sum of returns: on one surface this is the
/// centre range, across a depth edge a value in between, off both surfaces.
struct NoiseModel {
    bool range_noise = true;                ///< add Gaussian range noise
    double near_accuracy_mm = 10.0;         ///< datasheet +- up to accuracy_knee_mm
    double accuracy_knee_mm = 1000.0;       ///< range where the +- becomes a fraction
    double far_accuracy_fraction = 0.01;    ///< datasheet +- beyond the knee, fraction of range
    double coverage_factor = 2.0;           ///< the datasheet's +- is this many sigma
    double systematic_fraction = 0.5;       ///< share of sigma^2 drawn once per scan and face
    bool dropouts = true;                   ///< lose readings at grazing incidence
    double dropout_start_deg = 65.0;        ///< incidence where dropouts begin
    double dropout_full_deg = 85.0;         ///< incidence where every reading is lost
    double dropout_base_probability = 0.0;  ///< extra probability of a lost reading anywhere
    int beam_samples = 5;                   ///< sub-rays per beam; 1 = no mixed pixels
    /// Cast the sub-rays for every ray, not only near depth edges (slow; the reference the
    /// edge trigger is tested against).
    bool beam_everywhere = false;

    /// Standard deviation of one reading, mm, at true range `range_mm` (0 when range_noise is off).
    [[nodiscard]] double sigma_mm(double range_mm) const {
        if (!range_noise) return 0.0;
        const double bound = range_mm <= accuracy_knee_mm
                                 ? near_accuracy_mm
                                 : std::max(near_accuracy_mm, far_accuracy_fraction * range_mm);
        return bound / coverage_factor;
    }

    /// Probability that one reading is lost at this incidence angle (degrees from the normal).
    [[nodiscard]] double dropout_probability(double incidence_deg) const {
        if (!dropouts) return 0.0;
        double p = 0.0;
        if (incidence_deg >= dropout_full_deg) {
            p = 1.0;
        } else if (incidence_deg > dropout_start_deg) {
            const double x =
                (incidence_deg - dropout_start_deg) / (dropout_full_deg - dropout_start_deg);
            p = x * x * (3.0 - 2.0 * x);
        }
        return p + (1.0 - p) * dropout_base_probability;
    }

    /// Throws Error(kInvalidParameter) for values out of range (accuracies < 0, k <= 0, fractions
    /// outside [0, 1], start >= full or outside 0..90 deg, beam_samples outside 1..64).
    void validate() const;

    /// No noise, no dropouts, no mixed pixels: readings are the true ranges, rounded to 1 mm.
    [[nodiscard]] static NoiseModel ideal() {
        NoiseModel m;
        m.range_noise = false;
        m.dropouts = false;
        m.beam_samples = 1;
        return m;
    }
};

/// Standard normal deviates by Marsaglia's polar method on SplitMix64, so a seed gives the same
/// numbers with every standard library (std::normal_distribution does not), without sin/cos.
class GaussianSource {
  public:
    explicit GaussianSource(std::uint64_t seed) : rng_(seed) {}
    double uniform() { return rng_.uniform(); }
    double normal() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        double u, v, s;
        do {
            u = 2.0 * rng_.uniform() - 1.0;
            v = 2.0 * rng_.uniform() - 1.0;
            s = u * u + v * v;
        } while (s >= 1.0 || s == 0.0);
        const double f = std::sqrt(-2.0 * std::log(s) / s);
        spare_ = v * f;
        has_spare_ = true;
        return u * f;
    }

  private:
    SplitMix64 rng_;
    double spare_ = 0.0;
    bool has_spare_ = false;
};

}  // namespace surfgrow::scanner
