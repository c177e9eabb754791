#include "surfgrow/core/detail/grow_statistics.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace surfgrow::detail {

namespace {

constexpr std::size_t kMaxRangeBands = 1024;

}  // namespace

std::vector<LocalPlane> local_planes(const CubeIndex& index, const std::vector<Surface>& surfaces,
                                     std::span<const double> tolerance) {
    std::vector<LocalPlane> planes(surfaces.size());
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
        const Vec3f n = surfaces[k].normal.cast<float>();
        planes[k] = {n, n.dot(index.to_local(surfaces[k].centroid)),
                     static_cast<float>(tolerance[k])};
    }
    return planes;
}

/// Stage 4a: each surface's members (count, bounds, mean residual, largest distance), in the
/// index's float frame. Each thread owns a range of surface ids and visits their members in point
/// order, so every residual sum is added up in the same order whatever the thread count. Returns
/// the points registered.
std::uint64_t member_statistics(const CubeIndex& index, std::span<const std::int32_t> labels,
                                std::span<const double> tolerance, int threads,
                                std::vector<Surface>& surfaces) {
    const std::size_t surface_count = surfaces.size();
    const std::size_t n = labels.size();
    const std::vector<LocalPlane> planes = local_planes(index, surfaces, tolerance);
    std::vector<Vec3f> lo(surface_count, Vec3f::Constant(std::numeric_limits<float>::max()));
    std::vector<Vec3f> hi(surface_count, Vec3f::Constant(std::numeric_limits<float>::lowest()));
    std::vector<double> residual_sum(surface_count, 0.0);
    std::vector<float> max_distance(surface_count, 0.0f);
#pragma omp parallel num_threads(threads)
    {
        const auto parts = static_cast<std::size_t>(omp_get_num_threads());
        const auto part = static_cast<std::size_t>(omp_get_thread_num());
        const auto from = static_cast<std::uint32_t>(surface_count * part / parts);
        const auto count = static_cast<std::uint32_t>(surface_count * (part + 1) / parts) - from;
        for (std::size_t i = 0; i < n; ++i) {
            // One unsigned compare: also false for the unregistered (-1).
            const std::uint32_t k = static_cast<std::uint32_t>(labels[i]) - from;
            if (k >= count) continue;
            const std::size_t s = from + k;
            const Vec3f p = index.local_point(static_cast<std::uint32_t>(i));
            ++surfaces[s].point_count;
            lo[s] = lo[s].cwiseMin(p);
            hi[s] = hi[s].cwiseMax(p);
            const float d = planes[s].distance(p);
            residual_sum[s] += static_cast<double>(d);
            max_distance[s] = std::max(max_distance[s], d);
        }
    }
    std::uint64_t registered = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : registered)
    for (std::size_t k = 0; k < surface_count; ++k) {
        Surface& s = surfaces[k];
        registered += s.point_count;
        if (s.point_count == 0) continue;
        s.mean_residual = residual_sum[k] / s.point_count;
        // The tolerance reported bounds every member, those the leftover pass gave it included.
        s.tolerance = std::max(s.tolerance, static_cast<double>(max_distance[k]));
        s.bounds.add(index.origin() + lo[k].cast<double>());
        s.bounds.add(index.origin() + hi[k].cast<double>());
    }
    return registered;
}

/// Stage 4b: registration by range band, over the input in its order (integer counts: any split
/// of the work gives the same totals); the not-indexed mark becomes the unregistered label.
std::vector<RangeBand> range_bands(const CloudView& cloud, const Orientation& orient,
                                   double band_width, int threads,
                                   std::span<std::int32_t> input_labels) {
    const bool range_known = orient.range_known();
    const bool per_scan = orient.source == OrientationSource::kScanOrigins;
    std::vector<Vec3f> origins;  // relative to the cloud's offset: one, or one per scan
    if (per_scan)
        for (const Vec3d& o : cloud.scan_origins) origins.push_back(o.cast<float>());
    else
        origins.push_back(orient.origin.cast<float>());
    const auto inv_band = static_cast<float>(1.0 / band_width);
    const std::size_t n_in = input_labels.size();
    std::vector<std::vector<RangeBand>> thread_bands(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
    {
        std::vector<RangeBand>& mine = thread_bands[static_cast<std::size_t>(omp_get_thread_num())];
        if (range_known) mine.resize(kMaxRangeBands);
#pragma omp for schedule(static)
        for (std::size_t j = 0; j < n_in; ++j) {
            std::int32_t& l = input_labels[j];
            if (l == kNotIndexed) {
                l = -1;
                continue;
            }
            if (!range_known) continue;
            std::uint32_t o = 0;
            if (per_scan) {
                o = cloud.scan_index[j];
                if (o >= origins.size()) o = 0;
            }
            const float r = (cloud.points[j] - origins[o]).norm();
            // As std::min, but a NaN (a range from an infinitely far origin) goes to the last
            // band instead of an undefined cast.
            const float x = r * inv_band;
            const auto band =
                x < float(kMaxRangeBands - 1) ? static_cast<std::size_t>(x) : kMaxRangeBands - 1;
            ++mine[band].points;
            mine[band].registered += l >= 0 ? 1 : 0;
        }
    }
    std::vector<RangeBand> bands;
    if (!range_known) return bands;
    bands.resize(kMaxRangeBands);
    for (const auto& mine : thread_bands) {
        for (std::size_t b = 0; b < mine.size(); ++b) {
            bands[b].points += mine[b].points;
            bands[b].registered += mine[b].registered;
        }
    }
    while (!bands.empty() && bands.back().points == 0) bands.pop_back();
    for (std::size_t b = 0; b < bands.size(); ++b) {
        bands[b].from = double(b) * band_width;
        bands[b].to = double(b + 1) * band_width;
    }
    if (bands.size() == kMaxRangeBands)  // the last band is open-ended
        bands.back().to = std::numeric_limits<double>::infinity();
    return bands;
}

/// Stage 4c: every normal faces its home point's sensor (or +z when none is known). A guessed
/// frame origin that sees a surface edge-on (its plane passes near the origin: a map-frame
/// cloud's floor) says nothing about its side: that surface faces +z instead.
/// Returns the members of those surfaces.
std::uint64_t orient_normals(const CloudView& cloud, const Orientation& orient,
                             std::span<const std::uint32_t> original,
                             std::span<const std::uint32_t> home_of, double max_incidence_deg,
                             int threads, std::vector<Surface>& surfaces) {
    std::uint64_t edge_on = 0;
    // Edge-on: the origin lies within the grazing angle of the fitted plane (through the
    // centroid) or within its tolerance, where noise alone decides the side.
    const bool guessed = orient.source == OrientationSource::kFrameOrigin;
    const double cos_grazing = std::cos(max_incidence_deg * (std::numbers::pi / 180.0));
    auto seen_edge_on = [&](const Surface& s) {
        const Vec3d from_plane = orient.origin - s.centroid;
        return std::abs(s.normal.dot(from_plane)) <
               std::max(cos_grazing * from_plane.norm(), s.tolerance);
    };
    const bool per_scan = orient.source == OrientationSource::kScanOrigins;
    auto origin_of = [&](std::uint32_t sorted) -> Vec3d {
        if (per_scan) {
            const std::uint32_t scan = cloud.scan_index[original[sorted]];
            if (scan < cloud.scan_origins.size()) return cloud.scan_origins[scan];
        }
        return orient.origin;
    };
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : edge_on)
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
        Surface& s = surfaces[k];
        Vec3d towards = orient.source == OrientationSource::kUp
                            ? Vec3d::UnitZ()
                            : Vec3d(origin_of(home_of[k]) - s.home);
        if (guessed && seen_edge_on(s)) {
            towards = Vec3d::UnitZ();
            edge_on += s.point_count;
        }
        if (s.normal.dot(towards) < 0) s.normal = -s.normal;
    }
    return edge_on;
}

/// Stage 4d: best-fit registration can take every member of a surface; such surfaces are dropped
/// (ids stay in home order) and the labels renumbered. Returns how many were dropped.
std::uint64_t drop_empty_surfaces(int threads, std::vector<Surface>& surfaces,
                                  std::span<std::int32_t> input_labels) {
    const std::size_t count = surfaces.size();
    const auto kept = static_cast<std::size_t>(std::count_if(
        surfaces.begin(), surfaces.end(), [](const Surface& s) { return s.point_count > 0; }));
    if (kept == count) return 0;
    std::vector<std::int32_t> new_id(count, -1);
    std::size_t next = 0;
    for (std::size_t k = 0; k < count; ++k) {
        if (surfaces[k].point_count == 0) continue;
        new_id[k] = static_cast<std::int32_t>(next);
        surfaces[next++] = surfaces[k];
    }
    surfaces.resize(kept);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t j = 0; j < input_labels.size(); ++j) {
        std::int32_t& l = input_labels[j];
        if (l >= 0) l = new_id[static_cast<std::size_t>(l)];
    }
    return count - kept;
}

}  // namespace surfgrow::detail
