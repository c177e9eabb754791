// Taking a tilting scan with the real devices: the servo steps through the plan, the URG sweeps n
// times at each step, and what they report (the read-back angle, the sensor's time stamp, its
// identity) goes into the raw scan. The links are the caller's (serial ports, the emulator).
#pragma once

#include <functional>

#include "surfgrow/scanner/pose.hpp"
#include "surfgrow/scanner/raw_scan.hpp"
#include "surfgrow/scanner/scanner_spec.hpp"
#include "surfgrow/scanner/servo_driver.hpp"
#include "surfgrow/scanner/urg_driver.hpp"

namespace surfgrow::scanner {

/// Called after each tilt position: positions done, positions planned.
using AcquisitionProgress = std::function<void(int done, int planned)>;

/// Connects to both devices, checks that the sensor measures the plan's steps, then for each of
/// spec.tilt's positions tilts the servo, reads its angle back and takes spec.readings_per_ray
/// sweeps of spec.laser's steps. The scan holds the read-back angles (they place the rays, not
/// the plan's), the sensor's time stamp of each position's first sweep, and a note naming both
/// devices.
///
/// A device that fails mid-scan (DeviceError, dxl::ServoError after the drivers' retries) ends
/// the scan: what was taken is returned, marked partial (RawScan::partial, stop_reason says
/// why). A failure before the first position is complete is thrown as it came.
[[nodiscard]] RawScan acquire_scan(UrgDriver& urg, dxl::ServoDriver& servo, const ScannerSpec& spec,
                                   const Pose& pose, const AcquisitionProgress& progress = {});

}  // namespace surfgrow::scanner
