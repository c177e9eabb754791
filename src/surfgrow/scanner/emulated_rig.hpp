// The whole scanning tool without hardware: an emulated URG whose sweeps the simulator casts at
// the angle an emulated servo actually reached, so an acquisition through the real drivers (and,
// with ports, the real serial path) yields a scan with ground truth, faults included on demand.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/scanner/noise_model.hpp"
#include "surfgrow/scanner/pose.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"
#include "surfgrow/scanner/scanner_spec.hpp"
#include "surfgrow/scanner/scene.hpp"
#include "surfgrow/scanner/servo_emulator.hpp"
#include "surfgrow/scanner/urg_emulator.hpp"

namespace surfgrow::scanner {

/// How the emulated rig stands and misbehaves.
struct RigSetup {
    NoiseModel noise = {};
    Pose pose = Pose::Identity();  ///< where the rig stands in the scene (sensor to world)
    std::uint64_t seed = 1;
    UrgFaults urg_faults = {};
    dxl::ServoFaults servo_faults = {};
    std::uint8_t servo_id = 1;
    /// The laser's true tilt when the servo reads 0: a servo horn mounted a little turned, which
    /// the read-back angle cannot show (surfgrow calibrate estimates it). Within 10 deg.
    double tilt_zero_deg = 0.0;
};

class EmulatedRig {
  public:
    /// `spec`: the laser (within the URG-04LX's steps 44..725, front 384), the tilt plan's step
    /// (the sweep's neighbours for mixed pixels), n, and the true optical offset (which the
    /// acquisition's own spec may not know). `scene` must outlive the rig. The k-th position
    /// swept draws its rays' noise from their own streams of the seed (ScanSimulator::simulate's
    /// first_stream), and every sweep shares the scan's systematic offset per face, as in one
    /// simulated scan. Throws Error(kInvalidParameter) for a spec the URG cannot have.
    EmulatedRig(const Scene& scene, const ScannerSpec& spec, const RigSetup& setup = {});

    /// The sensor's bytes for a SCIP command line; the servo's for an instruction packet. Safe
    /// to call from the two ports' threads.
    [[nodiscard]] std::string urg_reply(std::string_view line);
    [[nodiscard]] std::string servo_reply(std::string_view packet);

    /// The ground-truth face id of every step of spec.laser for the servo position of `deg`
    /// (a read-back angle); empty if no sweep was taken there.
    [[nodiscard]] std::vector<std::int32_t> truth_at(double deg) const;

  private:
    // The n readings of every step of a sweep at the servo's present position, simulated once
    // per position; the k-th request there gets reading k (mod n).
    std::vector<std::uint32_t> sweep();

    const Scene& scene_;
    ScannerSpec spec_;
    RigSetup setup_;
    mutable std::mutex mutex_;
    UrgEmulator urg_;
    dxl::ServoEmulator servo_;
    std::int32_t cached_ticks_ = -1;       // the position the cached readings belong to
    std::uint64_t sweeps_ = 0;             // positions simulated so far
    std::vector<std::uint16_t> readings_;  // n per step at cached_ticks_
    int served_ = 0;                       // readings served at cached_ticks_
    std::map<std::int32_t, std::vector<std::int32_t>> truth_;  // by servo ticks
};

}  // namespace surfgrow::scanner
