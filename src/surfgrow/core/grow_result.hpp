// What surface growing returns: surfaces, a label per input point, and the statistics.
#pragma once

#include <cstdint>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/surface.hpp"

namespace surfgrow {

/// Points and registered points in one band of distance from the sensor.
struct RangeBand {
    double from = 0.0;
    double to = 0.0;
    std::uint64_t points = 0;
    std::uint64_t registered = 0;
};

/// Wall-clock seconds per stage (not part of the deterministic output).
struct StageTimes {
    double index = 0.0;   ///< cube index build
    double grow = 0.0;    ///< home points, PCA, registration
    double attach = 0.0;  ///< leftover pass
    double finish = 0.0;  ///< member statistics, orientation
    [[nodiscard]] double total() const { return index + grow + attach + finish; }
};

/// How a normal's side was chosen.
enum class OrientationSource {
    kScanOrigins,  ///< each point's own scan origin (fused clouds)
    kViewpoint,    ///< one viewpoint: given, or from the file (PCD VIEWPOINT)
    kFrameOrigin,  ///< none given; the frame origin is near the points (a sensor-frame scan)
    kUp,           ///< none given and the origin is far away (georeferenced): normals face +z
};

struct GrowStats {
    std::uint64_t points_in = 0;       ///< points in the cloud
    std::uint64_t invalid_points = 0;  ///< NaN or Inf coordinates: skipped
    std::uint64_t cropped_points = 0;  ///< outside the workspace crop: skipped
    std::uint64_t valid_points = 0;    ///< points grown (finite and inside the crop)
    std::uint64_t surfaces = 0;
    std::uint64_t registered_grown = 0;    ///< registered by growing alone (the paper's figure)
    std::uint64_t registered = 0;          ///< after the leftover pass
    std::uint64_t homes_tried = 0;         ///< home points given a neighbourhood search
    std::uint64_t rejected_sparse = 0;     ///< homes with fewer than min_pts neighbours (noise)
    std::uint64_t rejected_covered = 0;    ///< homes whose surface would take too few new points
    std::uint64_t rejected_nonplanar = 0;  ///< homes whose neighbourhood failed the plane test
    std::uint64_t adapted_surfaces = 0;    ///< surfaces grown with a radius above mu
    std::uint64_t released_by_refinement = 0;  ///< members beyond the tolerance of a refined plane
    std::uint64_t dropped_surfaces = 0;        ///< grown, then dropped: emptied or lone (kDisk)
    std::uint64_t lone_surfaces = 0;           ///< of those, in no plane with any neighbour
    std::uint64_t strip_surfaces = 0;  ///< grown by the strip test from the leftovers (kDisk)
    std::uint64_t edge_moves = 0;      ///< points the edge pass moved across an edge (fused, kDisk)
    std::uint64_t noise_points = 0;    ///< valid points left unregistered
    OrientationSource orientation = OrientationSource::kUp;
    /// kFrameOrigin: registered points on surfaces the guessed origin sees beyond the grazing
    /// limit (no sensor there could have measured them: they face +z instead). Many of them
    /// say the origin is not the sensor (a map-frame cloud): see origin_looks_wrong().
    std::uint64_t edge_on_points = 0;
    bool range_known = false;            ///< whether range bands could be measured
    Vec3d range_origin = Vec3d::Zero();  ///< where ranges are measured from (single origin)
    std::vector<RangeBand> range_bands;
    /// The measured noise (plane thickness sigma) by range band of width noise_band from the
    /// sensor, or one value for all ranges (noise_band 0); empty with the paper's plane test.
    std::vector<double> noise_sigma;
    double noise_band = 0.0;
    /// Fused clouds: the sigma of how far a scan's layer of a surface lies from the densest
    /// scan's there, along its rays, by range band of width layer_band (or one value,
    /// layer_band 0); empty for one scan.
    std::vector<double> layer_sigma;
    double layer_band = 0.0;
    StageTimes seconds;

    [[nodiscard]] double registered_fraction() const {
        return valid_points ? double(registered) / double(valid_points) : 0.0;
    }
    [[nodiscard]] double registered_grown_fraction() const {
        return valid_points ? double(registered_grown) / double(valid_points) : 0.0;
    }
    /// Registration is poor (under 90 %) and mostly because home points had too few neighbours
    /// within mu: mu is too small for the point spacing (or not in the cloud's units).
    [[nodiscard]] bool sparse_for_mu() const {
        if (valid_points == 0 || registered_fraction() >= 0.9) return false;
        return rejected_sparse >= rejected_nonplanar && rejected_sparse >= homes_tried / 4;
    }
    /// The normals faced a guessed frame origin that sees over 5 % of the registered points
    /// edge-on (a sensor-frame scan: about 1 %): it is probably not where the sensor stood.
    [[nodiscard]] bool origin_looks_wrong() const {
        return orientation == OrientationSource::kFrameOrigin &&
               double(edge_on_points) > 0.05 * double(registered);
    }
    /// Points per surface: the paper's data reduction (100 000 points -> 2 000 surfaces = 50x).
    [[nodiscard]] double data_reduction() const {
        return surfaces ? double(valid_points) / double(surfaces) : 0.0;
    }
};

struct GrowResult {
    std::vector<Surface> surfaces;     ///< ordered by the home point's cube (spatially coherent)
    std::vector<std::int32_t> labels;  ///< per input point: its surface, or -1
    GrowStats stats;
};

}  // namespace surfgrow
