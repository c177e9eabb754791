#include "surfgrow/scanner/scan_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "surfgrow/core/random.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow::scanner {

namespace {

constexpr int kMaxTiltReach = 64;  // beyond this, checking neighbours costs more than casting

// What the beam of one ray returns before noise.
struct BeamReturn {
    double range_m = 0.0;        // power-weighted blend of the sub-ray ranges
    double cos_incidence = 1.0;  // power-weighted cosine of the incidence angle
    std::int32_t face = -1;      // the one face every hitting sub-ray met, else -1
};

// Accumulates sub-ray hits into a BeamReturn, weighting each by the power it returns.
struct BeamBlend {
    double w_sum = 0.0, wr_sum = 0.0, wc_sum = 0.0;
    std::int32_t face = -1;
    bool any = false, one_face = true;

    void add(double t, double cos_incidence, std::int32_t face_id) {
        const double c = std::clamp(cos_incidence, 0.0, 1.0);
        const double w = (c + 1e-12) / (t * t);  // Lambertian return: cos / r^2
        w_sum += w;
        wr_sum += w * t;
        wc_sum += w * c;
        if (!any) face = face_id;
        one_face = one_face && face_id == face;
        any = true;
    }
    [[nodiscard]] BeamReturn result() const {
        return {wr_sum / w_sum, std::clamp(wc_sum / w_sum, 0.0, 1.0), one_face ? face : -1};
    }
};

}  // namespace

ScanSimulator::ScanSimulator(const Scene& scene, ScannerSpec spec, NoiseModel noise)
    : scene_(scene), scanner_(std::move(spec)), noise_(noise) {
    noise_.validate();
    // Centre sample plus a ring: each of the K samples stands for 1/K of the beam's cross-section,
    // the ring at the radius that splits the outer annulus's area in half.
    const ScannerSpec& s = scanner_.spec();
    const double half_angle = deg_to_rad(0.5 * s.laser.beam_divergence_deg);
    const int k = half_angle > 0.0 ? noise_.beam_samples : 1;
    beam_offsets_.emplace_back(0.0, 0.0);
    double ring = 0.0;
    if (k > 1) {
        ring = std::atan(std::sqrt(0.5 * (1.0 + 1.0 / k)) * std::tan(half_angle));
        for (int i = 0; i < k - 1; ++i) {
            const double phi = 6.283185307179586476925 * i / (k - 1);
            beam_offsets_.emplace_back(std::tan(ring) * std::cos(phi),
                                       std::tan(ring) * std::sin(phi));
        }
    }
    // Neighbours a sub-ray can reach: in the scan plane steps are step_deg apart; across it the
    // rays of adjacent tilts at pan p are tilt_step * |cos p| apart (tilting turns about y).
    const double pan_step = deg_to_rad(s.laser.step_deg);
    const double tilt_step = deg_to_rad(s.tilt.step_deg);
    step_reach_ = std::max(1, static_cast<int>(std::ceil(ring / pan_step)));
    tilt_reach_.resize(static_cast<std::size_t>(scanner_.step_count()));
    for (int j = 0; j < scanner_.step_count(); ++j) {
        const double spacing = tilt_step * std::abs(std::cos(scanner_.pan_rad(j)));
        const double reach = spacing > 0.0 ? std::ceil(ring / spacing) : 1e9;
        tilt_reach_[static_cast<std::size_t>(j)] =
            reach > kMaxTiltReach ? -1 : std::max(1, static_cast<int>(reach));
    }
}

SimulatedScan ScanSimulator::simulate(const Pose& pose, std::uint64_t seed) const {
    return simulate(pose, seed, 0);
}

SimulatedScan ScanSimulator::simulate(const Pose& pose, std::uint64_t seed,
                                      std::uint64_t first_stream) const {
    check_rigid(pose);
    const ScannerSpec& spec = scanner_.spec();
    const std::size_t rays = spec.rays();
    const int n = spec.readings_per_ray;
    const int steps = scanner_.step_count();
    const int tilts = scanner_.tilt_count();
    const double max_range_m = spec.laser.max_range_mm * 1e-3;
    const double min_mm = spec.laser.min_range_mm, max_mm = spec.laser.max_range_mm;
    const bool beams = beam_offsets_.size() > 1;

    SimulatedScan out;
    out.raw.spec = spec;
    out.raw.pose = pose;
    out.raw.readings_mm.assign(rays * static_cast<std::size_t>(n), 0);
    out.raw.truth_face_id.assign(rays, -1);
    out.true_range_m.assign(rays, std::numeric_limits<float>::quiet_NaN());
    out.true_normal.assign(rays, Vec3f::Zero());
    std::vector<std::int32_t> centre_face(rays, -1);
    std::vector<double> centre_t(rays, 0.0);
    std::vector<float> centre_cos(rays, 0.0f);

    const Mat3d world_rot = pose.linear();
    // Beam frame of (tilt, step) in the world: direction, in-plane and out-of-plane unit vectors.
    auto beam_frame = [&](int i, int j, Vec3d& dir, Vec3d& across, Vec3d& up) {
        const Mat3d rot = world_rot * scanner_.tilt_rotation(i);
        const Vec3d b = scanner_.beam_in_laser(j);
        dir = rot * b;
        across = rot * Vec3d(-b.y(), b.x(), 0.0);
        up = rot.col(2);
    };

    // Pass 1: the centre ray of every beam.
#pragma omp parallel for schedule(dynamic, 4) num_threads(resolve_threads(0))
    for (int i = 0; i < tilts; ++i) {
        const Vec3d origin = pose * scanner_.optical_centre(i);
        for (int j = 0; j < steps; ++j) {
            if (!scanner_.can_detect(j)) continue;
            const std::size_t ray = scanner_.ray_index(i, j);
            Vec3d dir, across, up;
            beam_frame(i, j, dir, across, up);
            Hit h;
            if (!scene_.intersect(Ray{origin, dir}, max_range_m, h)) continue;
            out.true_range_m[ray] = static_cast<float>(h.t);
            out.true_normal[ray] = h.normal.cast<float>();
            centre_face[ray] = h.face_id;
            centre_t[ray] = h.t;
            centre_cos[ray] = static_cast<float>(-h.normal.dot(dir));
        }
    }

    // Whether a neighbouring centre ray within the footprint's reach met another face.
    auto near_edge = [&](int i, int j) {
        const int reach = tilt_reach_[static_cast<std::size_t>(j)];
        if (reach < 0 || noise_.beam_everywhere) return true;
        const std::int32_t f = centre_face[scanner_.ray_index(i, j)];
        for (int dj = -step_reach_; dj <= step_reach_; ++dj) {
            const int jj = j + dj;
            if (jj < 0 || jj >= steps || !scanner_.can_detect(jj)) continue;
            for (int di = -reach; di <= reach; ++di) {
                const int ii = i + di;
                if (ii < 0 || ii >= tilts) continue;
                if (centre_face[scanner_.ray_index(ii, jj)] != f) return true;
            }
        }
        return false;
    };

    // The systematic part of the error: one standard normal per face of the scene for this scan
    // (a surface-dependent offset: colour, material, drift), scaled by sigma(r) at each reading.
    // Its own stream, apart from the rays' streams.
    std::vector<double> face_offset(scene_.faces().size());
    for (std::size_t f = 0; f < face_offset.size(); ++f)
        face_offset[f] = GaussianSource(mix_seed(~seed, f)).normal();
    const double sys_share = std::sqrt(noise_.systematic_fraction);
    const double rnd_share = std::sqrt(1.0 - noise_.systematic_fraction);

    // Pass 2: sub-rays near edges, then the n noisy readings of each beam.
#pragma omp parallel for schedule(dynamic, 4) num_threads(resolve_threads(0))
    for (int i = 0; i < tilts; ++i) {
        const Vec3d origin = pose * scanner_.optical_centre(i);
        for (int j = 0; j < steps; ++j) {
            if (!scanner_.can_detect(j)) continue;
            const std::size_t ray = scanner_.ray_index(i, j);
            BeamReturn br;
            if (beams && near_edge(i, j)) {
                Vec3d dir, across, up;
                beam_frame(i, j, dir, across, up);
                BeamBlend blend;
                if (centre_face[ray] >= 0)
                    blend.add(centre_t[ray], centre_cos[ray], centre_face[ray]);
                for (std::size_t k = 1; k < beam_offsets_.size(); ++k) {
                    const Eigen::Vector2d& o = beam_offsets_[k];
                    const Ray sub{origin, (dir + o.x() * across + o.y() * up).normalized()};
                    Hit h;
                    if (scene_.intersect(sub, max_range_m, h))
                        blend.add(h.t, -h.normal.dot(sub.direction), h.face_id);
                }
                if (!blend.any) continue;
                br = blend.result();
            } else {
                if (centre_face[ray] < 0) continue;
                br = {centre_t[ray], std::clamp<double>(centre_cos[ray], 0.0, 1.0),
                      centre_face[ray]};
            }
            out.raw.truth_face_id[ray] = br.face;

            const double range_mm = br.range_m * 1000.0;
            if (range_mm < min_mm || range_mm > max_mm) continue;  // beyond the sensor's reach
            GaussianSource g(mix_seed(seed, first_stream + ray));
            const double sigma = noise_.sigma_mm(range_mm);
            // A mixed pixel takes the offset of the face its centre met.
            const std::int32_t bias_face = br.face >= 0 ? br.face : centre_face[ray];
            const double z =
                bias_face >= 0 ? face_offset[static_cast<std::size_t>(bias_face)] : g.normal();
            const double bias = sys_share * sigma * z;
            const double p_drop =
                noise_.dropout_probability(rad_to_deg(std::acos(br.cos_incidence)));
            std::uint16_t* dst = &out.raw.readings_mm[ray * static_cast<std::size_t>(n)];
            for (int r = 0; r < n; ++r) {
                const double u = g.uniform();
                const double e = g.normal();
                if (u < p_drop) continue;
                const double v = std::round(range_mm + bias + rnd_share * sigma * e);
                if (v < min_mm || v > max_mm) continue;  // reported as no return
                dst[r] = static_cast<std::uint16_t>(v);
            }
        }
    }
    return out;
}

std::vector<SimulatedScan> ScanSimulator::simulate(const std::vector<Pose>& poses,
                                                   std::uint64_t seed) const {
    std::vector<SimulatedScan> scans;
    scans.reserve(poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k)
        scans.push_back(simulate(poses[k], mix_seed(seed, k)));
    return scans;
}

}  // namespace surfgrow::scanner
