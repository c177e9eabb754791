#include "surfgrow/eval/report_json.hpp"

#include <cmath>

#include "surfgrow/eval/metrics.hpp"

namespace surfgrow::eval {

namespace {

using nlohmann::json;

json number(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

json share(const Share& s) {
    return {{"points", s.points}, {"registered", s.registered}, {"fraction", number(s.fraction())}};
}

json distribution(const Distribution& d) {
    return {{"count", d.count},
            {"mean", number(d.mean)},
            {"median", number(d.median)},
            {"p95", number(d.p95)},
            {"max", number(d.max)}};
}

json bands_json(const std::vector<BandReport>& bands) {
    json out = json::array();
    for (const BandReport& b : bands)
        out.push_back({{"from_m", number(b.from_m)},
                       {"to_m", number(b.to_m)},
                       {"all", share(b.all)},
                       {"planar", share(b.planar)},
                       {"normal_deg", distribution(b.normal_deg)},
                       {"over_10", number(b.over_10)},
                       {"over_45", number(b.over_45)}});
    return out;
}

json incidence_json(const std::vector<IncidenceReport>& bands) {
    json out = json::array();
    for (const IncidenceReport& b : bands)
        out.push_back({{"from_deg", b.from_deg},
                       {"to_deg", b.to_deg},
                       {"planar", share(b.planar)},
                       {"normal_deg", distribution(b.normal_deg)},
                       {"over_10", number(b.over_10)},
                       {"over_45", number(b.over_45)}});
    return out;
}

}  // namespace

json to_json(const EvalReport& r, const std::vector<RequirementCheck>& checks) {
    json metric_values = json::object();
    for (const Metric& m : metrics(r)) metric_values[std::string(m.name)] = number(m.value);

    json planes = nullptr;
    if (r.planes.known)
        planes = {{"normal_deg", distribution(r.planes.normal_deg)},
                  {"over_10", number(r.planes.over_10)},
                  {"over_45", number(r.planes.over_45)},
                  {"bands", bands_json(r.planes.bands)},
                  {"incidence", incidence_json(r.planes.incidence)},
                  {"faces_scored", r.planes.faces_scored},
                  {"faces_detected", r.planes.faces_detected}};
    json faces = json::array();
    for (const FaceReport& f : r.faces) {
        if (f.points.points == 0 && f.surfaces == 0) continue;
        faces.push_back({{"id", f.id},
                         {"planar", f.planar},
                         {"points", f.points.points},
                         {"registered", f.points.registered},
                         {"surfaces", f.surfaces},
                         {"normal_median_deg", number(f.normal_median_deg)}});
    }
    json reqs = json::array();
    for (const RequirementCheck& c : checks)
        reqs.push_back(
            {{"requirement", c.requirement.text}, {"value", number(c.value)}, {"met", c.met}});

    return {
        {"format", "surfgrow-eval"},
        {"version", 1},
        {"options",
         {{"workspace_m", r.options.workspace_m},
          {"band_m", r.options.band_m},
          {"impure_below", r.options.impure_below},
          {"min_face_points", r.options.min_face_points}}},
        {"metrics", metric_values},
        {"points", r.points},
        {"finite_points", r.finite_points},
        {"surfaces", r.surfaces},
        {"range_known", r.range_known},
        {"registration",
         {{"all", share(r.all)},
          {"planar", share(r.planar)},
          {"planar_workspace", share(r.planar_workspace)},
          {"curved", share(r.curved)},
          {"unlabelled", share(r.unlabelled)},
          {"grown_fraction", number(r.registered_grown)},
          {"reported_fraction", number(r.registered_reported)}}},
        {"normals",
         {{"planar_deg", distribution(r.normal_deg)},
          {"planar_over_10", number(r.normal_over_10)},
          {"planar_over_45", number(r.normal_over_45)},
          {"planar_workspace_deg", distribution(r.normal_workspace_deg)},
          {"curved_deg", distribution(r.normal_curved_deg)},
          {"facing_sensor", share(r.facing_sensor)}}},
        {"surface_quality",
         {{"purity", number(r.purity)},
          {"purity_surface_mean", number(r.purity_surface_mean)},
          {"impure_surfaces", r.impure_surfaces},
          {"unlabelled_members", r.unlabelled_members},
          {"surface_normal_deg", distribution(r.surface_normal_deg)},
          {"plane_offset_m", distribution(r.plane_offset_m)},
          {"residual_m", distribution(r.residual_m)}}},
        {"coverage",
         {{"faces_with_points", r.faces_with_points},
          {"faces_grown", r.faces_grown},
          {"faces_missed", r.faces_missed},
          {"surfaces_per_face", number(r.surfaces_per_face)},
          {"data_reduction", number(r.data_reduction)}}},
        {"bands", bands_json(r.bands)},
        {"incidence", incidence_json(r.incidence)},
        {"through_planes", planes},
        {"faces", faces},
        {"requirements", reqs},
    };
}

}  // namespace surfgrow::eval
