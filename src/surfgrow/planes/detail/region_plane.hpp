// The plane of one region of patches: fitted to its member points, or on a map, the plane it had
// at the last call extended by the points it gained since (docs/planes-and-coverage.md, "Per
// region"; docs/scanner.md, "Mapping while scanning").
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/moments.hpp"
#include "surfgrow/core/surface.hpp"
#include "surfgrow/planes/bound_plane_memo.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/planes/patch_members.hpp"

namespace surfgrow::detail {

/// One region as compute_bound_planes hands it over: its patches (ascending) and everything per
/// patch the plane is made of.
struct RegionInput {
    std::span<const Surface> surfaces;
    const PatchMembers& members;
    std::span<const CentredMoments> moments;  ///< per patch, of its members
    std::span<const Aabb> boxes;              ///< per patch, of its members
    std::span<const std::uint32_t> patches;   ///< the region's, ascending
    const CentredMoments& all;                ///< pooled over its patches
    const Vec3d& judge;                       ///< add_judge over its patches
};

/// The median of `v` (0 when empty).
[[nodiscard]] double median_of(std::vector<double> v);

/// The least-squares plane of the region's member points, refitted to its inliers, oriented by
/// its patches' normals, with its frame, bounds and boundary polygons. With `state`, what
/// extend_region needs later (empty for a degenerate plane).
[[nodiscard]] BoundPlane fit_region(const RegionInput& region, const BoundPlaneConfig& cfg,
                                    RegionState* state = nullptr);

/// The plane of the region fit_region gives (the same normal, centroid and RMS: its fit reads
/// the member points, sampled alike), its boundary traced on `was`'s cell counts of the member
/// points instead of a raster of them all: the counts take out the members the last call saw of
/// was's patches that are another region's now (their first `known`), and take in those past
/// them (each of was's patches from its `known` count on, any other patch whole), in the frame of
/// was's last fit anew. The axes are that frame's turned with the normal. Nothing, and `state`
/// untouched, when was kept no counts (a degenerate plane), the region more than doubled (a
/// fit anew takes its new principal axis), the normal turned by more than kExtendDeg from that
/// frame, or the raster would outgrow kMaxRasterCells.
[[nodiscard]] std::optional<BoundPlane> extend_region(const RegionInput& region,
                                                      const FittedRegion& was,
                                                      std::span<const std::uint32_t> known,
                                                      const BoundPlaneConfig& cfg,
                                                      RegionState& state);

/// The region's plane as compute_bound_planes takes it, its points fitted once: extend_region's
/// where `was` is given (with a `state`) and it extends, else fit_region's.
[[nodiscard]] BoundPlane region_plane(const RegionInput& region, const FittedRegion* was,
                                      std::span<const std::uint32_t> known,
                                      const BoundPlaneConfig& cfg, RegionState* state);

/// The largest turn of a region's normal from the frame its boundary raster lies in, in
/// degrees: the raster's cells then lie within 0.004 % of their size of those on the plane.
inline constexpr double kExtendDeg = 0.5;

}  // namespace surfgrow::detail
