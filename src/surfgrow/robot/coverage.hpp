// Coverage goals and path (paper section 5.5): goal points whose blast discs cover every bound
// plane, an ordered sweep through them, and an approach pose per goal.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/surface.hpp"
#include "surfgrow/planes/bound_planes.hpp"
#include "surfgrow/planes/polygon2d.hpp"

namespace surfgrow {

/// Parameters of coverage planning. Lengths are in the cloud's units (defaults assume metres);
/// 0 means the default derived from the planes' mu.
struct CoverageConfig {
    double blast_radius = 0.0;    ///< a goal covers the disc of this radius around it (0: mu)
    double standoff = 0.3;        ///< tool distance from the goal along its approach axis
    double min_angle_deg = 5.0;   ///< the approach axis must lie at least this far from the normal
    double max_angle_deg = 40.0;  ///< ... and at most this far (paper: 5 to 40 degrees)
    /// The tilt used, within [min_angle_deg, max_angle_deg]; default: min_angle_deg.
    std::optional<double> tilt_deg;
    double sample_spacing = 0.0;  ///< coverage is planned on a grid this fine (0: blast_radius / 3)
    std::optional<Vec3d> start;   ///< tool position before the first goal; default: none
    int threads = 0;              ///< 0 = all cores; the result does not depend on it
};

/// The most goal candidates (points of the hexagonal lattice over the planes' extents) a plan may
/// need: a blast radius too small for its planes is refused before minutes of work.
inline constexpr double kMaxGoalCandidates = 1e8;
/// The planning grid (sample_spacing) is at least the blast radius over this.
inline constexpr double kMaxSamplesPerBlastRadius = 16;

/// Throws Error(kInvalidParameter) naming the first parameter out of range: every length within
/// float coordinates' range (length_limits.hpp), then each one's own rule.
void validate(const CoverageConfig& config);

/// One goal on a plane, in path order, with the tool's approach pose.
struct CoverageGoal {
    std::uint32_t plane = 0;              ///< index into BoundPlanes::planes
    std::uint32_t row = 0;                ///< sweep row within the plane (along its u axis)
    Vec3d position = Vec3d::Zero();       ///< on the plane
    Vec3d normal = Vec3d::UnitZ();        ///< the plane's oriented normal
    Vec3d direction = Vec3d::UnitX();     ///< sweep direction here (+-u_axis)
    Vec3d tool_position = Vec3d::Zero();  ///< position + standoff * (-tool_axis)
    Vec3d tool_axis = -Vec3d::UnitZ();    ///< unit, from the tool towards the goal (the jet)
    /// Tool frame: z = tool_axis, x = the sweep direction made orthogonal to z, y = z x x.
    /// Normalised with w >= 0.
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    double tilt_deg = 0.0;    ///< angle between -tool_axis and the normal
    bool from_home = false;   ///< placed at a surface's home point (else on the lattice or grid)
    bool transition = false;  ///< the first goal of a plane reached from another plane
};

/// What the plan achieves on one plane.
struct PlaneCoverage {
    std::uint32_t plane = 0;
    std::uint32_t goals = 0;
    std::uint32_t first_goal = 0;  ///< index of its first goal in CoveragePlan::goals
    double area = 0.0;
    double covered_fraction = 0.0;
};

struct CoverageStats {
    std::uint64_t goals = 0;
    std::uint64_t planes = 0;        ///< planes with goals
    std::uint64_t transitions = 0;   ///< moves from one plane to the next (planes - 1)
    double area = 0.0;               ///< registered area: the planes' polygons
    double covered_area = 0.0;       ///< within blast_radius of a goal on the same plane
    double coverage = 0.0;           ///< covered_area / area (0 when there is no area)
    double tool_path_length = 0.0;   ///< through the tool positions, in order
    double sweep_length = 0.0;       ///< ... of it within planes
    double transition_length = 0.0;  ///< ... of it between planes
    double goal_path_length = 0.0;   ///< through the goal points on the surfaces
};

struct CoveragePlan {
    std::vector<CoverageGoal> goals;       ///< in path order
    std::vector<PlaneCoverage> per_plane;  ///< in visiting order
    CoverageConfig config;                 ///< the parameters used, defaults resolved
    CoverageStats stats;
};

/// Goals on one plane in its 2D coordinates (BoundPlane::to_plane), before the path orders them.
struct PlaneGoals {
    std::vector<Vec2d> points;
    std::vector<std::uint32_t> rows;
    std::vector<std::uint8_t> from_home;
    double covered_fraction = 0.0;
};

/// What plan_coverage keeps from one call to the next (a map's planes, most of which stay as
/// they were from one scan to the next): each plane's goals, reused for a plane with the same
/// polygons, frame and patches whose home points are the same, planned with the same lengths.
/// The plan has the same bits as planned anew.
struct CoverageMemo {
    struct Plane {
        BoundPlane plane;          ///< its frame, polygons and patches (the rest is not read)
        std::vector<Vec3d> homes;  ///< of its patches
        PlaneGoals goals;
    };
    double blast_radius = -1, sample_spacing = -1;
    std::vector<Plane> planes;
    std::vector<std::int32_t> plane_from;  ///< per patch, the plane it is the first patch of
};

/// Plans goals and a path over bound planes.
///
/// Goals, per plane: first the points of a hexagonal lattice of circumradius blast_radius,
/// rows along the plane's u axis, that lie on the plane and add coverage (a hexagonal lattice is
/// the thinnest covering by discs); then, where discs around lattice points off the plane would
/// have been needed (along the boundary), a lazy greedy cover of what is left, preferring the
/// member surfaces' home points, else any grid point on the plane. Coverage is measured on an
/// independent grid twice as fine, so it is not 100 % by construction.
///
/// Path: boustrophedon within each plane (rows in v order, alternating direction along u);
/// planes in a short order (greedy nearest neighbour, then 2-opt with each plane's sweep run
/// either way, up to a budget of tested moves), distances between tool positions.
///
/// Pose: the tool trails its goal by `tilt` from the normal, so the jet leans forward into the
/// sweep direction: tool_axis = -(cos(tilt) n - sin(tilt) direction).
///
/// `surfaces` gives the home points for the greedy fill (may be empty). Throws
/// Error(kInvalidParameter) for a configuration out of range. Deterministic for any thread count.
///
/// With a `memo`, the goals of a plane it planned before are reused (CoverageMemo), and it is
/// refreshed.
[[nodiscard]] CoveragePlan plan_coverage(const BoundPlanes& planes,
                                         std::span<const Surface> surfaces,
                                         const CoverageConfig& config,
                                         CoverageMemo* memo = nullptr);

/// The same with a GrowResult's surfaces: what `surfgrow grow` calls after compute_bound_planes.
[[nodiscard]] inline CoveragePlan plan_coverage(const BoundPlanes& planes, const GrowResult& result,
                                                const CoverageConfig& config) {
    return plan_coverage(planes, result.surfaces, config);
}

}  // namespace surfgrow
