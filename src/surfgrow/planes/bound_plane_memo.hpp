// What bound planes keep from one call to the next on a map (pipeline/map.hpp), whose patches
// only gain points, at the end of the cloud: the member lists are extended by the new points,
// each patch's moments and box and which patches touch are recomputed only where a patch gained
// members, a region made of the same unchanged patches keeps its plane, and a region that changed
// traces its boundary on the cell counts it kept (detail::extend_region). The regions and their
// planes are those computed anew; a changed region's boundary lies within a raster cell of it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/moments.hpp"
#include "surfgrow/core/surface.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/planes/patch_members.hpp"
#include "surfgrow/planes/plane_raster.hpp"

namespace surfgrow {

/// How many of a region's member points lie in each cell of its boundary raster's lattice: the
/// cell (x, y) has its centre at base + cell * (x, y), and the counts cover x in [x0, x0 + width),
/// y in [y0, y0 + height), row-major. The lattice is the one its fit anew rasterised on (base its
/// origin), so a point always falls in the same cell; points leave as well as join.
struct CellCounts {
    Vec2d base = Vec2d::Zero();
    double cell = 1.0;
    long x0 = 0, y0 = 0;
    long width = 0, height = 0;
    std::vector<std::uint32_t> count;
};

/// What extending a region's plane by new points needs (detail::extend_region): the frame of
/// its last fit anew and the cell counts of its member points in it. Empty (no counts) for a
/// degenerate plane, which is always fitted anew.
struct RegionState {
    Vec3d normal = Vec3d::UnitZ();  ///< the plane's normal, u and v axes, and centroid
    Vec3d u_axis = Vec3d::UnitX();
    Vec3d v_axis = Vec3d::UnitY();
    Vec3d anchor = Vec3d::Zero();
    CellCounts cells;  ///< of the member points in that frame, before the closing
};

/// A region's plane as fitted, with what its fit read besides its patches' members.
struct FittedRegion {
    CentredMoments moments;  ///< pooled over its patches, in the order it grew
    Vec3d judge = Vec3d::Zero();
    BoundPlane plane;  ///< its `patches` are the region's, ascending
    RegionState state;
};

/// Each patch as the last call saw it, and the planes it fitted. Empty until a call fills it.
struct BoundPlaneMemo {
    // Per patch: what decides whether it is the same patch ...
    std::vector<Vec3d> homes;
    std::vector<Vec3d> normals;
    std::vector<double> radii;
    std::vector<std::uint32_t> neighbours;
    // ... and how many members it had, the last one's cloud index (0: none) ...
    std::vector<std::uint32_t> counts;
    std::vector<std::uint32_t> last;
    // ... their moments about its home point in member order, and their box.
    std::vector<Moments> moments;
    std::vector<Aabb> boxes;
    double reach = -1;                 ///< the adjacency distance `pairs` were found with
    std::vector<std::uint64_t> pairs;  ///< adjacent patches (pair_key), sorted
    /// The boundary lengths the planes were traced with (resolution, closing, simplification).
    double resolution = -1, closing_radius = -1, simplify_tolerance = -1;
    std::vector<FittedRegion> regions;
    std::vector<std::int32_t> region_from;  ///< per patch, the region it is the first patch of
    /// The member lists of the cloud's first `member_points` points, kept from the end of the
    /// last call: the next extends them by the points after (patch_members).
    PatchMembers members;
    std::size_t member_points = 0;
};

/// The member lists of (points, labels): the memo's, taken out of it and extended by the points
/// after those it covers, where it describes the same cloud (every patch it knows has as many
/// members, and its last is the same point with the same label); else collected anew. The same
/// lists either way.
[[nodiscard]] PatchMembers patch_members(BoundPlaneMemo& memo, std::span<const Vec3f> points,
                                         std::span<const std::int32_t> labels, std::size_t surfaces,
                                         int threads);

/// For each patch of (members, surfaces), how many of its first members the memo already holds:
/// its count in the memo where the patch is the memo's (the same home, normal, radius and
/// neighbours, at least as many members, the same one at that count), else 0. All 0, and `valid`
/// false, when any patch the memo knows fails that: the memo then describes other patches.
struct KnownMembers {
    bool valid = false;
    std::vector<std::uint32_t> count;
};
[[nodiscard]] KnownMembers known_members(const BoundPlaneMemo& memo, const PatchMembers& members,
                                         std::span<const Surface> surfaces);

/// Each patch's moments about its home point and box, from the memo's first known.count[s]
/// members on (all of them where none are known), in member order: the same bits as from the
/// first member. Patches without members keep empty moments and boxes.
void patch_sums(const BoundPlaneMemo& memo, const KnownMembers& known, const PatchMembers& members,
                std::span<const Surface> surfaces, std::vector<Moments>& moments,
                std::vector<Aabb>& boxes, int threads);

/// Records the patches as they are now in the memo (after patch_sums and the pairs).
void remember_patches(BoundPlaneMemo& memo, const PatchMembers& members,
                      std::span<const Surface> surfaces, std::vector<Moments> moments,
                      std::vector<Aabb> boxes, double reach, std::vector<std::uint64_t> pairs);

/// The memo's region whose first patch is `patches[0]` (ascending), traced with the same lengths;
/// null otherwise.
[[nodiscard]] const FittedRegion* remembered_region(const BoundPlaneMemo& memo,
                                                    std::span<const std::uint32_t> patches,
                                                    const BoundPlaneConfig& config);

/// The memo's plane of a region (`patches` ascending, none of them changed: `changed` marks those
/// that did), when it fitted the same one: the same patches, pooled moments and judge, traced with
/// the same lengths. Null otherwise.
[[nodiscard]] const FittedRegion* remembered_plane(const BoundPlaneMemo& memo,
                                                   std::span<const std::uint32_t> patches,
                                                   std::span<const std::uint8_t> changed,
                                                   const CentredMoments& moments,
                                                   const Vec3d& judge,
                                                   const BoundPlaneConfig& config);

/// Records the regions' planes and states (every region, before they are published) in the memo.
void remember_planes(BoundPlaneMemo& memo, std::size_t patches,
                     std::span<const CentredMoments> moments, std::span<const Vec3d> judges,
                     std::span<const BoundPlane> planes, std::vector<RegionState> states,
                     const BoundPlaneConfig& config);

}  // namespace surfgrow
