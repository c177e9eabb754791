// The simulator that stands in for the hardware: ray-casts a scene with the sensor's errors.
#pragma once

#include <cstdint>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/scanner/noise_model.hpp"
#include "surfgrow/scanner/raw_scan.hpp"
#include "surfgrow/scanner/scene.hpp"
#include "surfgrow/scanner/tilting_scanner.hpp"

namespace surfgrow::scanner {

/// A simulated scan: the raw scan (with truth_face_id filled) plus per-ray ground truth.
struct SimulatedScan {
    RawScan raw;
    /// Per ray: the true range of the beam's centre, metres (NaN where it met nothing).
    std::vector<float> true_range_m;
    /// Per ray: the true unit normal at the centre hit, world frame, facing the sensor (zero where
    /// it met nothing).
    std::vector<Vec3f> true_normal;
};

/// Simulates scans of a scene. Each ray draws its random numbers from its own stream
/// mix_seed(seed, ray index), and each face its systematic offset from mix_seed(~seed, face id),
/// so a scan depends only on (scene, spec, noise, pose, seed): the same bytes for any number of
/// threads.
///
/// Two passes: the centre ray of every beam is cast first; a beam's sub-rays (mixed pixels) are
/// then cast only where a neighbouring centre ray within the footprint's reach met another face
/// or nothing, i.e. near depth and face edges. Elsewhere all sub-rays would meet the centre's face
/// and the blend is the centre range. (A part thinner than the ray spacing that no centre ray
/// meets is missed, as by the real sensor's sampling.) NoiseModel::beam_everywhere turns the
/// trigger off.
class ScanSimulator {
  public:
    /// Keeps a reference to `scene`, which must outlive the simulator. Throws
    /// Error(kInvalidParameter) for an invalid spec or noise model.
    ScanSimulator(const Scene& scene, ScannerSpec spec = {}, NoiseModel noise = {});

    [[nodiscard]] const TiltingScanner& scanner() const { return scanner_; }
    [[nodiscard]] const NoiseModel& noise() const { return noise_; }

    /// One scan from `pose` (sensor to world). Throws Error(kInvalidParameter) for a non-rigid
    /// pose.
    [[nodiscard]] SimulatedScan simulate(const Pose& pose, std::uint64_t seed) const;
    /// The same with ray r drawing from stream mix_seed(seed, first_stream + r): pieces of one
    /// scan simulated apart (the emulated rig's sweeps) share its faces' systematic offsets and
    /// never repeat a ray's noise.
    [[nodiscard]] SimulatedScan simulate(const Pose& pose, std::uint64_t seed,
                                         std::uint64_t first_stream) const;

    /// One scan per pose; scan k uses seed mix_seed(seed, k).
    [[nodiscard]] std::vector<SimulatedScan> simulate(const std::vector<Pose>& poses,
                                                      std::uint64_t seed) const;

  private:
    const Scene& scene_;
    TiltingScanner scanner_;
    NoiseModel noise_;
    /// Sub-ray offsets across the beam: (in scan plane, out of it), as tangents of the angle.
    std::vector<Eigen::Vector2d> beam_offsets_;
    /// Per step: how many tilt rows on each side the beam's footprint can reach (-1: too many to
    /// check, always cast the sub-rays); and how many steps.
    std::vector<int> tilt_reach_;
    int step_reach_ = 1;
};

}  // namespace surfgrow::scanner
