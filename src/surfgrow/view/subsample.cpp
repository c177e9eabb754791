#include "surfgrow/view/subsample.hpp"

#include <algorithm>

#include "surfgrow/core/error.hpp"

namespace surfgrow::view {

namespace {

// splitmix64's finaliser: a bijection on 64 bits, so no two indices share a key.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

}  // namespace

std::vector<std::uint32_t> choose_points(const CloudView& cloud, std::size_t max_points) {
    if (cloud.size() > 0xffffffffULL)
        throw Error(ErrorCode::kInvalidParameter, "the viewer takes at most 2^32 points");
    std::vector<std::uint32_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (is_finite(cloud.points[i])) keep.push_back(static_cast<std::uint32_t>(i));
    if (keep.size() <= max_points) return keep;
    // The max_points smallest hashes: exactly max_points points, a uniform-looking choice.
    std::vector<std::uint64_t> keyed(keep.size());
    for (std::size_t k = 0; k < keep.size(); ++k)
        keyed[k] = (mix(keep[k]) & ~0xffffffffULL) | keep[k];  // hash high, index low: no ties
    auto nth = keyed.begin() + static_cast<std::ptrdiff_t>(max_points);
    std::nth_element(keyed.begin(), nth, keyed.end());
    keep.resize(max_points);
    for (std::size_t k = 0; k < max_points; ++k) keep[k] = static_cast<std::uint32_t>(keyed[k]);
    std::sort(keep.begin(), keep.end());
    return keep;
}

}  // namespace surfgrow::view
