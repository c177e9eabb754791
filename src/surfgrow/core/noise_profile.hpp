// How thick a plane is in this cloud, by range: the measured noise that the disk test's thickness
// limit and the registration tolerance are tied to.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace surfgrow {

/// One measurement: the RMS thickness sqrt(lambda_min) of a neighbourhood that passed the
/// relative tests at the smallest radius it could, and its range from the sensor (< 0: unknown).
struct ThicknessSample {
    double range = -1;
    double thickness = 0;
};

/// The median plane thickness per range band, read off sampled neighbourhoods of the cloud
/// itself, so that no sensor model is assumed. Bands with too few samples take the value of
/// their neighbours: interpolated between two measured bands, the nearest one's below the first,
/// and beyond the last growing in proportion to range (range noise grows with range).
class NoiseProfile {
  public:
    NoiseProfile() = default;  ///< nothing measured: known() is false

    /// From samples; `band` is the width of the range bands, `floor` the smallest sigma reported
    /// (rounding of the coordinates). Samples without a range make one band for all ranges.
    NoiseProfile(std::span<const ThicknessSample> samples, double band, double floor);

    [[nodiscard]] bool known() const { return !sigma_.empty(); }
    /// The noise sigma at `range` (any range when the samples had none). Requires known().
    [[nodiscard]] double sigma(double range) const;
    [[nodiscard]] double band() const { return band_; }
    /// Per band from range 0: the sigma used (measured or filled in).
    [[nodiscard]] const std::vector<double>& sigmas() const { return sigma_; }

    /// Fewest samples for a band's own median.
    static constexpr std::size_t kMinSamples = 16;

  private:
    double band_ = 0;  // 0: one band for all ranges
    std::vector<double> sigma_;
};

}  // namespace surfgrow
