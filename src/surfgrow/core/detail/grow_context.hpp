// What the stages of surface growing share (internal): the index cut into slabs, where the sensor
// stood for each point, the noise measured, a thread's scratch buffers, a home point's
// neighbourhood, and the surfaces' planes in the index's frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/detail/bulk_allocator.hpp"
#include "surfgrow/core/detail/neighbourhood.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"
#include "surfgrow/core/noise_profile.hpp"
#include "surfgrow/core/plane_fit.hpp"
#include "surfgrow/core/plane_test.hpp"
#include "surfgrow/core/surface.hpp"

namespace surfgrow::detail {

using Range = CubeIndex::Range;

// A scan's range bias moves its layer along the rays: by cos(incidence) of it along the normal,
// counted as at least this much (grazing layers are few and thin on the ground).
constexpr double kMinLayerCos = 0.25;

// A leftover beside surfaces that it does not fit looks for others up to this many mu away (the
// leftover pass), and a strip reaches along its face by steps this long (extend_strips).
constexpr double kMissRadiusPerMu = 2.0;

/// A slab: all cubes whose x coordinate lies in one interval; a contiguous run of cubes.
struct Slab {
    std::uint32_t cube_begin = 0;
    std::uint32_t cube_end = 0;
};

/// A surface as it is grown, before statistics: home (sorted index), radius, fit.
struct GrownSurface {
    std::uint32_t home = 0;
    float radius = 0;
    float tolerance = 0;  // registration tolerance
    std::uint32_t neighbours = 0;
    PlaneFit fit;     // centroid relative to the home point, local frame
    Moments moments;  // about the home point, for normal pooling
};

/// Per-thread scratch reused across slabs: no allocation per home point. A cache line of its
/// own: two threads' vectors side by side would share one, and every push_back would bounce it.
struct alignas(64) Scratch {
    BulkVector<GrownSurface> grown;  // every slab this thread grew, one after another
    std::vector<std::uint32_t> order;
    std::vector<Range> table;
    std::vector<Range> runs;
    std::vector<TakenPoint> taken;
};

/// Where the sensor stood for each point, in the index's local frame (kDisk's grazing test).
struct SensorSight {
    std::vector<Vec3f> origins;  // local; empty: unknown
    // The grazing test needs a sensor the cloud or the user names (scan origins, a viewpoint):
    // a frame origin is only a guess, and a map-frame cloud has it on its floor.
    bool named = false;
    std::span<const std::uint32_t> scan_index;  // input order; empty: origins[0] for all
    std::span<const std::uint32_t> original;    // sorted index -> input index

    /// Whether the points come from more than one scan (a fused cloud).
    [[nodiscard]] bool fused() const { return !scan_index.empty() && origins.size() > 1; }
    /// The scan of sorted point `i` (0 unless fused).
    [[nodiscard]] std::uint32_t scan_of(std::uint32_t i) const {
        return scan_index.empty() ? 0 : scan_index[original[i]];
    }
    /// Direction from the sensor to sorted point `i` at local position `p`; zero when unknown.
    [[nodiscard]] Vec3d towards(std::uint32_t i, const Vec3f& p) const {
        if (origins.empty()) return Vec3d::Zero();
        std::uint32_t o = 0;
        if (!scan_index.empty()) {
            o = scan_index[original[i]];
            if (o >= origins.size()) o = 0;
        }
        return (p - origins[o]).cast<double>();
    }
};

struct GrowContext {
    const CubeIndex& index;
    const GrowerConfig& config;
    std::span<std::int32_t> labels;  // sorted order; during growing: the home's sorted index
    std::span<float> distance;       // sorted order: a registered point's distance to its plane
    const SensorSight& sight;
    const NoiseProfile& noise;   // measured plane thickness by range (kDisk); may be unknown
    const NoiseProfile& layers;  // fused clouds: the scans' offsets from each other, by range
};

/// A home point's neighbourhood at the radius where the search stopped.
struct Neighbourhood {
    PlaneVerdict verdict = PlaneVerdict::kThick;
    double radius = 0;
    double range = -1;  // from the sensor; < 0: unknown
    Moments moments;
    PlaneFit fit;
    std::span<const Range> runs;  // the cube runs that cover the ball
    double tolerance = 0;         // registration tolerance (accepted neighbourhoods)
};

/// A surface's plane in the index's float frame, for per-point passes.
struct LocalPlane {
    Vec3f normal;
    float offset;     // normal . centroid (local)
    float tolerance;  // registration tolerance of this surface
    [[nodiscard]] float distance(const Vec3f& p) const { return std::abs(normal.dot(p) - offset); }
    [[nodiscard]] bool holds(const Vec3f& p) const { return distance(p) <= tolerance; }
};

/// Each surface's plane in the index's frame, with its registration tolerance.
std::vector<LocalPlane> local_planes(const CubeIndex& index, const std::vector<Surface>& surfaces,
                                     std::span<const double> tolerance);

/// Chooses where normals should face and where ranges are measured from.
struct Orientation {
    OrientationSource source = OrientationSource::kUp;
    Vec3d origin = Vec3d::Zero();  // single origin (viewpoint or frame origin)

    /// Whether each point's range from a sensor is known (not when normals merely face +z).
    [[nodiscard]] bool range_known() const { return source != OrientationSource::kUp; }
};

}  // namespace surfgrow::detail
