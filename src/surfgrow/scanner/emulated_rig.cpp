#include "surfgrow/scanner/emulated_rig.hpp"

#include <cmath>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/scanner/dynamixel.hpp"

namespace surfgrow::scanner {

EmulatedRig::EmulatedRig(const Scene& scene, const ScannerSpec& spec, const RigSetup& setup)
    : scene_(scene),
      spec_(spec),
      setup_(setup),
      urg_([this] { return sweep(); }, setup.urg_faults),
      servo_(setup.servo_id, 40, setup.servo_faults) {
    spec_.validate();
    check_rigid(setup_.pose);
    if (!(std::abs(setup_.tilt_zero_deg) <= 10))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"the emulated servo's zero error ", std::to_string(setup_.tilt_zero_deg),
                         " deg is beyond 10 deg"}));
    const LaserSpec& l = spec_.laser;
    if (l.first_step < UrgEmulator::kFirstStep || l.last_step > UrgEmulator::kLastStep ||
        l.front_step != UrgEmulator::kFrontStep)
        throw Error(
            ErrorCode::kInvalidParameter,
            cat({"the emulated URG-04LX measures steps ", std::to_string(UrgEmulator::kFirstStep),
                 "..", std::to_string(UrgEmulator::kLastStep), " around front step ",
                 std::to_string(UrgEmulator::kFrontStep),
                 "; this laser asks for others (use urg04lx-682)"}));
}

std::string EmulatedRig::urg_reply(std::string_view line) {
    const std::lock_guard lock(mutex_);
    return urg_.reply(line);
}

std::string EmulatedRig::servo_reply(std::string_view packet) {
    const std::lock_guard lock(mutex_);
    return servo_.reply(packet);
}

std::vector<std::int32_t> EmulatedRig::truth_at(double deg) const {
    const std::lock_guard lock(mutex_);
    const auto it = truth_.find(dxl::ticks_of(deg));
    return it == truth_.end() ? std::vector<std::int32_t>{} : it->second;
}

std::vector<std::uint32_t> EmulatedRig::sweep() {  // called by urg_ under mutex_
    const auto steps = static_cast<std::size_t>(spec_.laser.steps());
    const auto n = static_cast<std::size_t>(spec_.readings_per_ray);
    const std::int32_t ticks = servo_.position();
    if (ticks != cached_ticks_) {
        // Three tilt rows around the servo's true angle, so the middle one's beams see their
        // neighbours for mixed pixels as in a whole simulated scan.
        ScannerSpec s = spec_;
        s.tilt.first_deg = dxl::degrees_of(ticks) + setup_.tilt_zero_deg - s.tilt.step_deg;
        s.tilt.positions = 3;
        const ScanSimulator sim(scene_, s, setup_.noise);
        const std::uint64_t first_stream = sweeps_++ * 3 * steps;
        const SimulatedScan rows = sim.simulate(setup_.pose, setup_.seed, first_stream);
        readings_.assign(rows.raw.readings_mm.begin() + static_cast<std::ptrdiff_t>(steps * n),
                         rows.raw.readings_mm.begin() + static_cast<std::ptrdiff_t>(2 * steps * n));
        truth_[ticks].assign(
            rows.raw.truth_face_id.begin() + static_cast<std::ptrdiff_t>(steps),
            rows.raw.truth_face_id.begin() + static_cast<std::ptrdiff_t>(2 * steps));
        cached_ticks_ = ticks;
        served_ = 0;
    }
    const std::size_t k = static_cast<std::size_t>(served_++) % n;
    std::vector<std::uint32_t> out(UrgEmulator::kSteps, 0);
    for (std::size_t j = 0; j < steps; ++j)
        out[static_cast<std::size_t>(spec_.laser.first_step) + j] = readings_[j * n + k];
    return out;
}

}  // namespace surfgrow::scanner
