// Surface growing (paper section 4.2): random home points, PCA, registration.
#pragma once

#include <cstdint>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"

namespace surfgrow {

/// The cube index growing works on (the paper's stage 1) and what building it found. Stages after
/// growing that index the same points (the occupancy grid) can reuse it instead of building their
/// own.
struct GrowIndex {
    CubeIndex index;           ///< the points of grown_point_mask(cloud, config), cube side mu
    std::uint64_t points = 0;  ///< points in the cloud it was built from
    std::uint64_t cropped_points = 0;  ///< finite points outside the workspace crop
    double seconds = 0.0;              ///< time to build it
};

/// Grows planar surface patches over a point cloud.
///
/// For each home point, drawn at random (seeded) among points not yet registered: gather the
/// points within mu through the cube index; with at least min_pts of them, fit a plane by PCA;
/// if eq. (2) holds, register the unregistered points within mu of the home point and within the
/// plane tolerance of the plane as one surface. A home point without support is rejected as noise.
///
/// Threads: space is cut into slabs along x, at least two neighbourhood radii wide; even slabs
/// grow in parallel, then odd ones, so two surfaces grown at once can never reach the same point.
/// Each slab draws its home points from its own stream of the seed. The result is therefore the
/// same, byte for byte, for any number of threads.
class SurfaceGrower {
  public:
    /// Throws Error(kInvalidParameter) if the configuration is out of range.
    explicit SurfaceGrower(GrowerConfig config);

    [[nodiscard]] const GrowerConfig& config() const { return config_; }

    /// Grows surfaces over `cloud`. An empty cloud (or one with no valid point) gives no surfaces.
    [[nodiscard]] GrowResult grow(const CloudView& cloud) const;

    /// The cube index of `cloud` for this configuration.
    [[nodiscard]] GrowIndex index(const CloudView& cloud) const;
    /// Grows surfaces over `cloud` through `index`, which index(cloud) built from the same cloud
    /// with the same configuration; same result as grow(cloud). Throws Error(kInvalidParameter)
    /// when the index is of a cloud of another size.
    [[nodiscard]] GrowResult grow(const CloudView& cloud, const GrowIndex& index) const;

  private:
    GrowerConfig config_;
};

/// One-call helper: SurfaceGrower(config).grow(cloud).
[[nodiscard]] inline GrowResult grow_surfaces(const CloudView& cloud,
                                              const GrowerConfig& config = {}) {
    return SurfaceGrower(config).grow(cloud);
}

}  // namespace surfgrow
