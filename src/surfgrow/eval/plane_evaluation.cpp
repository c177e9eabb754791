#include "surfgrow/eval/plane_evaluation.hpp"

namespace surfgrow::eval {

std::vector<Surface> surfaces_through_planes(std::span<const Surface> surfaces,
                                             const BoundPlanes& planes) {
    std::vector<Surface> out(surfaces.begin(), surfaces.end());
    for (std::size_t k = 0; k < out.size() && k < planes.plane_of_patch.size(); ++k) {
        const std::int32_t p = planes.plane_of_patch[k];
        if (p < 0) continue;
        const BoundPlane& plane = planes.planes[static_cast<std::size_t>(p)];
        // Keep the patch's own orientation: the plane's normal faces the majority's sensor side.
        out[k].normal = plane.normal.dot(out[k].normal) >= 0 ? plane.normal : Vec3d(-plane.normal);
        out[k].centroid =
            out[k].centroid - plane.plane().signed_distance(out[k].centroid) * plane.normal;
    }
    return out;
}

void add_plane_figures(EvalReport& report, const CloudView& cloud, const GrowOutcome& grown,
                       const BoundPlanes& planes, std::span<const scanner::Face> faces) {
    const std::vector<Surface> through = surfaces_through_planes(grown.surfaces, planes);
    const EvalReport p =
        evaluate(cloud, GrowOutcome{through, grown.labels, grown.stats}, faces, report.options);
    EvalReport::ThroughPlanes& t = report.planes;
    t.known = true;
    t.normal_deg = p.normal_deg;
    t.over_10 = p.normal_over_10;
    t.over_45 = p.normal_over_45;
    t.bands = p.bands;
    t.incidence = p.incidence;
    std::vector<std::uint8_t> planar(faces.size(), 0);
    for (std::size_t f = 0; f < faces.size(); ++f) planar[f] = faces[f].planar() ? 1 : 0;
    const FaceDetection d =
        correct_detections(cloud.labels, plane_labels(planes, grown.labels), 0.8, 500, planar);
    t.faces_scored = d.faces;
    t.faces_detected = d.correct;
}

}  // namespace surfgrow::eval
