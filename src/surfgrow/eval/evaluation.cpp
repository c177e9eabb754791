#include "surfgrow/eval/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::eval {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;
constexpr std::size_t kMaxBands = 64;  // the last one is open-ended

[[noreturn]] void mismatch(const std::string& message) {
    throw Error(ErrorCode::kInvalidParameter, message);
}

void check_inputs(const CloudView& cloud, const GrowOutcome& grown,
                  std::span<const scanner::Face> faces, const EvalOptions& o) {
    if (!(o.workspace_m > 0) || !(o.band_m > 0) || !std::isfinite(o.workspace_m) ||
        !std::isfinite(o.band_m))
        mismatch("evaluation: workspace and band width must be positive");
    if (!(o.impure_below >= 0 && o.impure_below <= 1))
        mismatch("evaluation: the impurity threshold must lie in [0, 1]");
    if (!cloud.empty() && !cloud.has_labels())
        mismatch("evaluation: the cloud carries no ground-truth labels (one face id per point)");
    if (grown.labels.size() != cloud.size())
        mismatch(cat({"evaluation: the result has ", std::to_string(grown.labels.size()),
                      " point labels for a cloud of ", std::to_string(cloud.size()),
                      " points: not a result of this cloud"}));
    for (std::size_t k = 0; k < faces.size(); ++k) {
        if (faces[k].id != static_cast<std::int32_t>(k))
            mismatch(cat({"evaluation: truth face ", std::to_string(k), " has id ",
                          std::to_string(faces[k].id)}));
    }
    const auto n_faces = static_cast<std::int64_t>(faces.size());
    const auto n_surf = static_cast<std::int64_t>(grown.surfaces.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (cloud.labels[i] < -1 || cloud.labels[i] >= n_faces)
            mismatch(cat({"evaluation: point ", std::to_string(i), " has truth face ",
                          std::to_string(cloud.labels[i]), " but the scene has ",
                          std::to_string(n_faces), " faces"}));
        if (grown.labels[i] < -1 || grown.labels[i] >= n_surf)
            mismatch(cat({"evaluation: point ", std::to_string(i), " is registered to surface ",
                          std::to_string(grown.labels[i]), " of ", std::to_string(n_surf)}));
    }
}

// Where point i was seen from: its own scan's origin, or the cloud's viewpoint.
std::optional<Vec3d> origin_of(const CloudView& cloud, std::size_t i) {
    if (cloud.has_scan_index() && cloud.scan_index[i] < cloud.scan_origins.size())
        return cloud.scan_origins[cloud.scan_index[i]];
    if (cloud.viewpoint) return *cloud.viewpoint;
    return std::nullopt;
}

struct BandAccumulator {
    Share all;
    Share planar;
    std::vector<double> errors;
};

constexpr double kIncidenceBandDeg = 15.0;
constexpr std::size_t kIncidenceBands = 6;

void count(Share& s, bool registered) {
    ++s.points;
    s.registered += registered ? 1 : 0;
}

}  // namespace

double share_above(std::span<const double> values, double threshold) {
    if (values.empty()) return kNaN;
    const auto over =
        std::count_if(values.begin(), values.end(), [&](double v) { return v > threshold; });
    return static_cast<double>(over) / static_cast<double>(values.size());
}

double EvalReport::worst_band_planar(std::uint64_t min_points) const {
    double worst = kNaN;
    for (const BandReport& b : bands) {
        if (b.planar.points < min_points) continue;
        const double f = b.planar.fraction();
        if (!(worst <= f)) worst = f;
    }
    return worst;
}

double Share::fraction() const {
    return points ? static_cast<double>(registered) / static_cast<double>(points) : kNaN;
}

EvalReport evaluate(const CloudView& cloud, const GrowOutcome& grown,
                    std::span<const scanner::Face> faces, const EvalOptions& options) {
    check_inputs(cloud, grown, faces, options);
    EvalReport r;
    r.options = options;
    r.points = cloud.size();
    r.surfaces = grown.surfaces.size();
    r.registered_grown = grown.stats ? grown.stats->registered_grown_fraction() : kNaN;
    r.registered_reported = grown.stats ? grown.stats->registered_fraction() : kNaN;

    std::vector<double> planar_err, workspace_err, curved_err, residual;
    std::vector<std::vector<double>> face_err(faces.size());
    std::vector<Share> face_share(faces.size());
    std::vector<BandAccumulator> bands;
    std::vector<BandAccumulator> incidence(kIncidenceBands);
    // (surface << 32 | face) of every registered point with a truth face, for purity.
    std::vector<std::uint64_t> pairs;
    pairs.reserve(cloud.size());

    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!is_finite(cloud.points[i])) continue;
        ++r.finite_points;
        const Vec3d p = cloud.points[i].cast<double>();
        const Vec3d world = p + cloud.offset;
        const std::int32_t truth = cloud.labels[i];
        const std::int32_t sid = grown.labels[i];
        const bool registered = sid >= 0;
        const scanner::Face* face = truth >= 0 ? &faces[static_cast<std::size_t>(truth)] : nullptr;
        const bool planar = face && face->planar();

        count(r.all, registered);
        count(face ? (planar ? r.planar : r.curved) : r.unlabelled, registered);
        if (face) count(face_share[static_cast<std::size_t>(truth)], registered);

        const std::optional<Vec3d> origin = origin_of(cloud, i);
        BandAccumulator* band = nullptr;
        bool in_workspace = false;
        if (origin) {
            r.range_known = true;
            const double range = (p - *origin).norm();
            in_workspace = range <= options.workspace_m;
            const auto b = static_cast<std::size_t>(
                std::min(range / options.band_m, static_cast<double>(kMaxBands - 1)));
            if (b >= bands.size()) bands.resize(b + 1);
            band = &bands[b];
            count(band->all, registered);
            if (planar) count(band->planar, registered);
            if (planar && in_workspace) count(r.planar_workspace, registered);
        }
        const Vec3d truth_normal = face ? face->normal_at(world) : Vec3d::Zero();
        BandAccumulator* inc = nullptr;
        if (origin && planar) {
            const Vec3d sight = p - *origin;
            const double cos_i = std::abs(truth_normal.dot(sight)) / std::max(sight.norm(), 1e-300);
            const double deg = std::acos(std::min(1.0, cos_i)) * kDegPerRad;
            inc = &incidence[std::min(static_cast<std::size_t>(deg / kIncidenceBandDeg),
                                      kIncidenceBands - 1)];
            count(inc->planar, registered);
        }
        if (!registered) continue;

        const Surface& s = grown.surfaces[static_cast<std::size_t>(sid)];
        residual.push_back(std::abs(s.normal.dot(p - s.centroid)));
        if (!face) {
            ++r.unlabelled_members;
            continue;
        }
        pairs.push_back(static_cast<std::uint64_t>(sid) << 32 | static_cast<std::uint32_t>(truth));
        const double err = axis_angle_between(s.normal, truth_normal) * kDegPerRad;
        face_err[static_cast<std::size_t>(truth)].push_back(err);
        if (planar) {
            planar_err.push_back(err);
            if (band) band->errors.push_back(err);
            if (inc) inc->errors.push_back(err);
            if (in_workspace) workspace_err.push_back(err);
        } else {
            curved_err.push_back(err);
        }
        if (origin) {
            // The true normal turned toward this point's own sensor; the grown one must agree.
            const Vec3d towards = *origin - p;
            const double side = truth_normal.dot(towards) >= 0 ? 1.0 : -1.0;
            count(r.facing_sensor, s.normal.dot(side * truth_normal) > 0);
        }
    }

    r.normal_over_10 = share_above(planar_err, 10.0);
    r.normal_over_45 = share_above(planar_err, 45.0);
    r.normal_deg = summarize(planar_err);
    r.normal_workspace_deg = summarize(workspace_err);
    r.normal_curved_deg = summarize(curved_err);
    r.residual_m = summarize(residual);
    r.data_reduction =
        r.surfaces ? static_cast<double>(r.finite_points) / static_cast<double>(r.surfaces) : kNaN;

    // Purity: each surface's majority face among its labelled members (ties: the lower id).
    std::sort(pairs.begin(), pairs.end());
    std::vector<std::uint32_t> surfaces_on_face(faces.size(), 0);
    std::vector<double> surface_normal_err, plane_offset;
    std::uint64_t majority_sum = 0, labelled_sum = 0, purity_surfaces = 0;
    double purity_sum = 0.0;
    for (std::size_t a = 0; a < pairs.size();) {
        const std::uint64_t sid = pairs[a] >> 32;
        std::size_t b = a, best_count = 0, total = 0;
        std::uint32_t best_face = 0;
        while (b < pairs.size() && pairs[b] >> 32 == sid) {
            const auto face = static_cast<std::uint32_t>(pairs[b]);
            std::size_t e = b;
            while (e < pairs.size() && pairs[e] == pairs[b]) ++e;
            if (e - b > best_count) {
                best_count = e - b;
                best_face = face;
            }
            total += e - b;
            b = e;
        }
        a = b;
        majority_sum += best_count;
        labelled_sum += total;
        const double purity = static_cast<double>(best_count) / static_cast<double>(total);
        purity_sum += purity;
        ++purity_surfaces;
        if (purity < options.impure_below) ++r.impure_surfaces;
        ++surfaces_on_face[best_face];
        const scanner::Face& f = faces[best_face];
        if (f.planar()) {
            const Surface& s = grown.surfaces[sid];
            surface_normal_err.push_back(axis_angle_between(s.normal, f.normal) * kDegPerRad);
            plane_offset.push_back(std::abs(f.plane().signed_distance(s.centroid + cloud.offset)));
        }
    }
    r.purity =
        labelled_sum ? static_cast<double>(majority_sum) / static_cast<double>(labelled_sum) : kNaN;
    r.purity_surface_mean =
        purity_surfaces ? purity_sum / static_cast<double>(purity_surfaces) : kNaN;
    r.surface_normal_deg = summarize(surface_normal_err);
    r.plane_offset_m = summarize(plane_offset);

    std::uint64_t surfaces_on_grown = 0;
    for (std::size_t k = 0; k < faces.size(); ++k) {
        FaceReport fr;
        fr.id = static_cast<std::int32_t>(k);
        fr.planar = faces[k].planar();
        fr.points = face_share[k];
        fr.surfaces = surfaces_on_face[k];
        fr.normal_median_deg = summarize(face_err[k]).median;
        if (fr.points.points > 0) ++r.faces_with_points;
        if (fr.surfaces > 0) {
            ++r.faces_grown;
            surfaces_on_grown += fr.surfaces;
        } else if (fr.points.points >= options.min_face_points) {
            ++r.faces_missed;
        }
        r.faces.push_back(fr);
    }
    r.surfaces_per_face =
        r.faces_grown ? static_cast<double>(surfaces_on_grown) / static_cast<double>(r.faces_grown)
                      : kNaN;

    for (std::size_t b = 0; b < bands.size(); ++b) {
        BandReport br;
        br.from_m = static_cast<double>(b) * options.band_m;
        br.to_m = b + 1 == kMaxBands ? std::numeric_limits<double>::infinity()
                                     : static_cast<double>(b + 1) * options.band_m;
        br.all = bands[b].all;
        br.planar = bands[b].planar;
        br.over_10 = share_above(bands[b].errors, 10.0);
        br.over_45 = share_above(bands[b].errors, 45.0);
        br.normal_deg = summarize(bands[b].errors);
        r.bands.push_back(br);
    }
    if (r.range_known) {
        for (std::size_t b = 0; b < kIncidenceBands; ++b) {
            IncidenceReport ir;
            ir.from_deg = static_cast<double>(b) * kIncidenceBandDeg;
            ir.to_deg = static_cast<double>(b + 1) * kIncidenceBandDeg;
            ir.planar = incidence[b].planar;
            ir.over_10 = share_above(incidence[b].errors, 10.0);
            ir.over_45 = share_above(incidence[b].errors, 45.0);
            ir.normal_deg = summarize(incidence[b].errors);
            r.incidence.push_back(ir);
        }
    }
    return r;
}

EvalReport evaluate(const CloudView& cloud, const GrowResult& result,
                    std::span<const scanner::Face> faces, const EvalOptions& options) {
    return evaluate(cloud, GrowOutcome{result.surfaces, result.labels, &result.stats}, faces,
                    options);
}

}  // namespace surfgrow::eval
