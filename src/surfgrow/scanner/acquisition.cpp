#include "surfgrow/scanner/acquisition.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

namespace surfgrow::scanner {

namespace {

std::string identity_note(const UrgIdentity& id, int servo_id) {
    return "sensor: " + id.vendor + " / " + id.product + " / firmware " + id.firmware +
           " / protocol " + id.protocol + " / serial " + id.serial + " (steps " +
           std::to_string(id.first_step) + ".." + std::to_string(id.last_step) + ", front " +
           std::to_string(id.front_step) + ", " + std::to_string(id.min_mm) + ".." +
           std::to_string(id.max_mm) + " mm)\nservo: DYNAMIXEL protocol 2.0, id " +
           std::to_string(servo_id);
}

}  // namespace

RawScan acquire_scan(UrgDriver& urg, dxl::ServoDriver& servo, const ScannerSpec& spec,
                     const Pose& pose, const AcquisitionProgress& progress) {
    spec.validate();
    check_rigid(pose);
    const UrgIdentity id = urg.connect();
    const LaserSpec& laser = spec.laser;
    if (laser.first_step < id.first_step || laser.last_step > id.last_step)
        throw DeviceError("URG: it measures steps " + std::to_string(id.first_step) + ".." +
                          std::to_string(id.last_step) + ", the laser spec asks for " +
                          std::to_string(laser.first_step) + ".." +
                          std::to_string(laser.last_step) + " (choose the urg04lx-682 laser)");
    if (laser.front_step != id.front_step)
        throw DeviceError("URG: its front step is " + std::to_string(id.front_step) +
                          ", the laser spec's " + std::to_string(laser.front_step));
    servo.connect();

    RawScan scan;
    scan.spec = spec;
    scan.pose = pose;
    scan.note = identity_note(id, servo.id());
    const int planned = spec.tilt.positions;
    const auto steps = static_cast<std::size_t>(laser.steps());
    const auto n = static_cast<std::size_t>(spec.readings_per_ray);
    scan.readings_mm.reserve(spec.readings());
    for (int i = 0; i < planned; ++i) {
        std::vector<std::uint16_t> position(steps * n);
        double angle = 0.0;
        std::uint32_t time_ms = 0;
        try {
            angle = servo.tilt_to(spec.tilt.tilt_deg(i));
            for (std::size_t k = 0; k < n; ++k) {
                const std::vector<std::uint32_t> mm = urg.scan(laser.first_step, laser.last_step);
                if (k == 0) time_ms = urg.last_time_stamp_ms();
                for (std::size_t j = 0; j < steps; ++j)  // 18-bit values beyond 65535 mm: no range
                    position[j * n + k] =
                        static_cast<std::uint16_t>(std::min<std::uint32_t>(mm[j], 65535));
            }
        } catch (const std::runtime_error& e) {  // DeviceError, dxl::ServoError
            if (i == 0) throw;
            scan.spec.tilt.positions = i;
            scan.planned_positions = planned;
            scan.stop_reason = e.what();
            return scan;
        }
        scan.readings_mm.insert(scan.readings_mm.end(), position.begin(), position.end());
        scan.tilt_read_deg.push_back(angle);
        scan.sensor_time_ms.push_back(time_ms);
        if (progress) progress(i + 1, planned);
    }
    try {
        urg.close();
    } catch (const DeviceError&) {  // the scan is whole; a laser left on harms nothing
    }
    return scan;
}

}  // namespace surfgrow::scanner
