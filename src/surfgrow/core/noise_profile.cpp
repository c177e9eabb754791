#include "surfgrow/core/noise_profile.hpp"

#include <algorithm>
#include <cmath>

namespace surfgrow {

namespace {

double median(std::vector<double>& v) {
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

constexpr std::size_t kMaxBands = 4096;

// One sigma for all ranges: the median of every sample, if there are enough; none otherwise.
std::vector<double> one_for_all(std::span<const ThicknessSample> samples, double floor) {
    std::vector<double> all;
    for (const ThicknessSample& s : samples) all.push_back(s.thickness);
    if (all.size() < NoiseProfile::kMinSamples) return {};
    return {std::max(median(all), floor)};
}

}  // namespace

NoiseProfile::NoiseProfile(std::span<const ThicknessSample> samples, double band, double floor) {
    bool ranged = band > 0;
    for (const ThicknessSample& s : samples) ranged = ranged && s.range >= 0;
    if (!ranged) {
        sigma_ = one_for_all(samples, floor);
        return;
    }
    band_ = band;
    std::vector<std::vector<double>> by_band;
    for (const ThicknessSample& s : samples) {
        const auto b = static_cast<std::size_t>(std::min(s.range / band, double(kMaxBands - 1)));
        if (b >= by_band.size()) by_band.resize(b + 1);
        by_band[b].push_back(s.thickness);
    }
    std::vector<double> measured(by_band.size(), -1);
    std::size_t first = by_band.size(), last = 0;
    for (std::size_t b = 0; b < by_band.size(); ++b) {
        if (by_band[b].size() < kMinSamples) continue;
        measured[b] = std::max(median(by_band[b]), floor);
        first = std::min(first, b);
        last = b;
    }
    if (first == by_band.size()) {  // too few in every band: one value for all
        band_ = 0;
        sigma_ = one_for_all(samples, floor);
        return;
    }
    sigma_.assign(last + 1, 0);
    std::size_t prev = first;
    for (std::size_t b = 0; b <= last; ++b) {
        if (b <= first) {
            sigma_[b] = measured[first];
        } else if (measured[b] >= 0) {
            // Bands between two measured ones: linear between them.
            for (std::size_t g = prev + 1; g < b; ++g) {
                const double t = double(g - prev) / double(b - prev);
                sigma_[g] = (1 - t) * measured[prev] + t * measured[b];
            }
            sigma_[b] = measured[b];
            prev = b;
        }
    }
}

double NoiseProfile::sigma(double range) const {
    if (band_ <= 0) return sigma_.front();
    const double b = range / band_;
    if (b < double(sigma_.size())) return sigma_[static_cast<std::size_t>(std::max(b, 0.0))];
    // Beyond the last measured band: in proportion to range from that band's middle.
    const double last_mid = (double(sigma_.size()) - 0.5) * band_;
    return sigma_.back() * range / last_mid;
}

}  // namespace surfgrow
