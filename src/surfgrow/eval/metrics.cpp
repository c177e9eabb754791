#include "surfgrow/eval/metrics.hpp"

#include <limits>

namespace surfgrow::eval {

std::vector<Metric> metrics(const EvalReport& r) {
    constexpr double mm = 1000.0;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    return {
        {"registered", r.all.fraction(), "fraction", "finite points registered to a surface"},
        {"registered_grown", r.registered_grown, "fraction",
         "registered by the paper's loop alone (before the leftover pass), as the grower counted"},
        {"registered_planar", r.planar.fraction(), "fraction",
         "points on planar truth faces registered"},
        {"registered_workspace", r.planar_workspace.fraction(), "fraction",
         "points on planar truth faces within the workspace radius registered"},
        {"registered_curved", r.curved.fraction(), "fraction",
         "points on cylinder sides registered"},
        {"registered_unlabelled", r.unlabelled.fraction(), "fraction",
         "points on no truth face (mixed pixels) registered"},
        {"normal_median", r.normal_deg.median, "deg",
         "median normal error of registered points on planar faces"},
        {"normal_p95", r.normal_deg.p95, "deg", "95th percentile of the same"},
        {"normal_mean", r.normal_deg.mean, "deg", "mean of the same"},
        {"normal_over_10", r.normal_over_10, "fraction",
         "share of registered points on planar faces more than 10 degrees off"},
        {"normal_over_45", r.normal_over_45, "fraction",
         "share of registered points on planar faces more than 45 degrees off"},
        {"registered_worst_band", r.worst_band_planar(), "fraction",
         "lowest planar registered share over the range bands with >= 1000 planar points"},
        {"planes_normal_p95", r.planes.known ? r.planes.normal_deg.p95 : kNaN, "deg",
         "95th percentile normal error with each point given its bound plane's normal"},
        {"planes_normal_over_45", r.planes.known ? r.planes.over_45 : kNaN, "fraction",
         "share of the same more than 45 degrees off"},
        {"faces_detected",
         r.planes.known && r.planes.faces_scored
             ? double(r.planes.faces_detected) / double(r.planes.faces_scored)
             : kNaN,
         "fraction",
         "planar faces with >= 500 points that a bound plane detects (SegComp, T = 0.8)"},
        {"normal_workspace_median", r.normal_workspace_deg.median, "deg",
         "median normal error on planar faces within the workspace radius"},
        {"normal_workspace_p95", r.normal_workspace_deg.p95, "deg", "95th percentile of the same"},
        {"normal_curved_median", r.normal_curved_deg.median, "deg",
         "median normal error of registered points on cylinder sides (true normal radial)"},
        {"facing_sensor", r.facing_sensor.fraction(), "fraction",
         "registered points whose surface normal faces their own sensor's side of the face"},
        {"purity", r.purity, "fraction",
         "share of surfaces' labelled members from each surface's majority face"},
        {"purity_surface_mean", r.purity_surface_mean, "fraction", "mean purity over surfaces"},
        {"impure_surfaces", static_cast<double>(r.impure_surfaces), "count",
         "surfaces with purity below the threshold"},
        {"surface_normal_median", r.surface_normal_deg.median, "deg",
         "median over surfaces of the normal error against the majority face"},
        {"plane_offset_median_mm", r.plane_offset_m.median * mm, "mm",
         "median over surfaces of the centroid's distance to the majority face's plane"},
        {"residual_mean_mm", r.residual_m.mean * mm, "mm",
         "mean distance of registered points to their surface's plane"},
        {"residual_p95_mm", r.residual_m.p95 * mm, "mm", "95th percentile of the same"},
        {"surfaces", static_cast<double>(r.surfaces), "count", "surfaces grown"},
        {"surfaces_per_face", r.surfaces_per_face, "ratio",
         "mean number of surfaces per truth face that has any"},
        {"faces_missed", static_cast<double>(r.faces_missed), "count",
         "truth faces with enough points but no surface"},
        {"data_reduction", r.data_reduction, "ratio", "finite points per surface"},
    };
}

std::vector<std::string_view> metric_names() {
    std::vector<std::string_view> names;
    for (const Metric& m : metrics(EvalReport{})) names.push_back(m.name);
    return names;
}

}  // namespace surfgrow::eval
