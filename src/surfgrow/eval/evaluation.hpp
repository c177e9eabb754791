// Accuracy of grown surfaces against the ground truth of a scanned scene (docs/evaluation.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/surface.hpp"
#include "surfgrow/eval/distribution.hpp"
#include "surfgrow/scanner/primitives.hpp"

namespace surfgrow::eval {

/// Points of one kind and how many of them a surface took.
struct Share {
    std::uint64_t points = 0;
    std::uint64_t registered = 0;
    /// registered / points; NaN when there are no points.
    [[nodiscard]] double fraction() const;
};

/// One band of range from each point's own scan origin.
struct BandReport {
    double from_m = 0.0;
    double to_m = 0.0;        ///< infinity for the last, open-ended band
    Share all;                ///< every finite point in the band
    Share planar;             ///< points whose truth face is planar
    Distribution normal_deg;  ///< per-point normal error of the planar points registered
    double over_10 = 0.0;     ///< share of those more than 10 degrees off (NaN: none)
    double over_45 = 0.0;     ///< share of those more than 45 degrees off (NaN: none)
};

/// One band of incidence: the angle between a planar point's true normal and its line of sight.
struct IncidenceReport {
    double from_deg = 0.0;
    double to_deg = 0.0;
    Share planar;             ///< planar points seen at this incidence
    Distribution normal_deg;  ///< per-point normal error of those registered
    double over_10 = 0.0;     ///< share of those more than 10 degrees off (NaN: none)
    double over_45 = 0.0;     ///< share of those more than 45 degrees off (NaN: none)
};

/// One ground-truth face.
struct FaceReport {
    std::int32_t id = -1;
    bool planar = true;
    Share points;                  ///< points whose truth label is this face
    std::uint32_t surfaces = 0;    ///< surfaces whose majority face this is
    double normal_median_deg = 0;  ///< median per-point normal error on it (NaN: none registered)
};

struct EvalOptions {
    /// "Within the workspace": at most this far from the point's own scan origin, metres. The
    /// paper's workspace radius is about 1 m (section 5.1).
    double workspace_m = 1.0;
    double band_m = 0.5;  ///< width of the range bands, metres
    /// A surface whose purity is below this counts as impure.
    double impure_below = 0.9;
    /// A face with at least this many points that no surface has as its majority face is
    /// counted as missed.
    std::uint64_t min_face_points = 50;
};

/// What surface growing produced for the cloud: surfaces and one surface id (or -1) per point,
/// in the cloud's frame and units (metres). `stats` is optional and supplies registered_grown.
struct GrowOutcome {
    std::span<const Surface> surfaces;
    std::span<const std::int32_t> labels;
    const GrowStats* stats = nullptr;
};

/// Every figure of the evaluation. Fractions are in [0, 1], angles in degrees, lengths in metres;
/// a figure that cannot be computed (no points of that kind, no scan origin) is NaN.
struct EvalReport {
    std::uint64_t points = 0;         ///< points in the cloud
    std::uint64_t finite_points = 0;  ///< points with finite coordinates (the rest are ignored)
    std::uint64_t surfaces = 0;

    // Registration, by the truth of each finite point.
    Share all;                       ///< every finite point
    Share planar;                    ///< truth face planar (rectangles, box faces, discs)
    Share curved;                    ///< truth face a cylinder's side
    Share unlabelled;                ///< no truth face: mixed pixels across edges, or nothing
    Share planar_workspace;          ///< planar points within workspace_m of their scan origin
    double registered_grown = 0.0;   ///< GrowStats: registered by the paper's loop alone
    double registered_reported = 0;  ///< GrowStats: registered as the grower counted it

    // Normals: angle between the normal of the surface a point was registered to and the true
    // normal of the point's face at that point, as lines (0..90 degrees).
    Distribution normal_deg;            ///< planar points
    double normal_over_10 = 0.0;        ///< share of registered planar points > 10 deg off
    double normal_over_45 = 0.0;        ///< share of registered planar points > 45 deg off
    Distribution normal_workspace_deg;  ///< planar points within the workspace
    Distribution normal_curved_deg;     ///< points on cylinder sides (true normal: radial)
    /// Oriented: of the registered points with a truth face and a known scan origin, those whose
    /// surface normal lies on the same side of the face as the point's own sensor.
    Share facing_sensor;

    // Surfaces against their majority face.
    double purity = 0.0;                   ///< share of labelled members from the majority face
    double purity_surface_mean = 0.0;      ///< mean over surfaces of each one's purity
    std::uint64_t impure_surfaces = 0;     ///< surfaces with purity below impure_below
    std::uint64_t unlabelled_members = 0;  ///< registered points with no truth face
    Distribution surface_normal_deg;       ///< each surface's normal vs its majority face (planar)
    Distribution plane_offset_m;  ///< each surface's centroid from its majority face's plane
    Distribution residual_m;      ///< |distance| of every registered point to its plane

    // Coverage.
    std::uint64_t faces_with_points = 0;  ///< truth faces with at least one point
    std::uint64_t faces_grown = 0;        ///< truth faces that are some surface's majority face
    std::uint64_t faces_missed = 0;       ///< faces with >= min_face_points points and no surface
    double surfaces_per_face = 0.0;       ///< mean over faces_grown of the surfaces on each
    double data_reduction = 0.0;          ///< finite points per surface (the paper's figure)

    bool range_known = false;  ///< whether points have a scan origin (bands, workspace, facing)
    EvalOptions options;
    std::vector<BandReport> bands;
    std::vector<IncidenceReport> incidence;  ///< 15-degree bands from 0 to 90 (range known)
    std::vector<FaceReport> faces;

    /// The same normal figures with every registered point given its bound plane's normal
    /// (planes.json), and SegComp's correct detection of the planar faces by the bound planes;
    /// filled by add_plane_figures() (plane_evaluation.hpp) where planes are known.
    struct ThroughPlanes {
        bool known = false;
        Distribution normal_deg;
        double over_10 = 0.0;
        double over_45 = 0.0;
        std::vector<BandReport> bands;
        std::vector<IncidenceReport> incidence;
        std::uint64_t faces_scored = 0;    ///< planar faces with >= 500 points
        std::uint64_t faces_detected = 0;  ///< of those, correctly detected (T = 0.8)
    } planes;

    /// The lowest registered share of planar points over the range bands holding at least
    /// `min_points` planar points (NaN: none does).
    [[nodiscard]] double worst_band_planar(std::uint64_t min_points = 1000) const;
};

/// Evaluates `grown` against the truth. `cloud` carries the truth face id of every point in
/// PointCloud::labels (-1: none), and where known each point's scan origin (scan_index and
/// scan_origins, or viewpoint). `faces` are the scene's faces in world coordinates (cloud
/// coordinates plus cloud.offset), indexed by id: Scene::faces() or a truth-faces file.
///
/// Throws Error(kInvalidParameter) when the inputs do not belong together: no truth labels, a
/// label count other than the point count, a truth id beyond `faces`, a surface id beyond
/// `grown.surfaces`, or options out of range.
[[nodiscard]] EvalReport evaluate(const CloudView& cloud, const GrowOutcome& grown,
                                  std::span<const scanner::Face> faces,
                                  const EvalOptions& options = {});

/// Share of `values` above `threshold` (NaN when empty).
[[nodiscard]] double share_above(std::span<const double> values, double threshold);

/// The same, for a GrowResult held in memory.
[[nodiscard]] EvalReport evaluate(const CloudView& cloud, const GrowResult& result,
                                  std::span<const scanner::Face> faces,
                                  const EvalOptions& options = {});

}  // namespace surfgrow::eval
