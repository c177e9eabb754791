// Talking to a URG over SCIP 2.0: the handshake, the sensor's identity and scans, with retries
// where a reply is lost or damaged. The link (a serial port, USB-ACM, the emulator) is the
// caller's.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/scanner/scip.hpp"

namespace surfgrow::scanner {

/// Sends one command's bytes and returns the reply's bytes up to and including the empty line
/// that ends it, or an empty string when none came within the link's time-out. MD/MS replies
/// are not read through it.
using UrgLink = std::function<std::string(std::string_view command)>;

/// The sensor refused, stayed silent or kept sending damaged replies: what, and after how many
/// attempts ("URG: no reply to GD0044072501 in 3 attempts (time-out): unplugged?").
class DeviceError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// What the sensor says it is (VV and PP).
struct UrgIdentity {
    std::string vendor, product, firmware, protocol, serial;
    int min_mm = 0, max_mm = 0;                         ///< DMIN, DMAX
    int steps_per_turn = 0;                             ///< ARES (URG-04LX: 1024)
    int first_step = 0, last_step = 0, front_step = 0;  ///< AMIN, AMAX, AFRT
    int rpm = 0;                                        ///< SCAN
};

class UrgDriver {
  public:
    /// `attempts`: how often a command is sent before DeviceError (at least 1).
    explicit UrgDriver(UrgLink link, int attempts = 3);

    /// Switches to SCIP 2.0, reads VV and PP, and turns the laser on. Throws DeviceError.
    UrgIdentity connect();

    /// One scan (GD): mm per step from `first` to `last` (0 where there was no echo, below 20 the
    /// sensor's error codes). Each request carries its own tag, so a late reply to an earlier
    /// one is never taken for it; a lost or damaged reply is asked for again; a laser found off
    /// is turned on. Throws DeviceError after `attempts`.
    std::vector<std::uint32_t> scan(int first, int last);

    /// Turns the laser off (QT). Throws DeviceError.
    void close();

    /// The sensor's time stamp (ms, 24 bits) of the last scan() returned.
    [[nodiscard]] std::uint32_t last_time_stamp_ms() const { return last_time_stamp_ms_; }

    /// Commands sent again after a lost or damaged reply, so far.
    [[nodiscard]] int retries() const { return retries_; }

  private:
    // Sends `code` (tagged unless `tagged` is false) until a well-formed reply to it arrives.
    scip::Reply request(const std::string& code, bool tagged = true);

    UrgLink link_;
    int attempts_;
    int retries_ = 0;
    unsigned next_tag_ = 0;
    std::uint32_t last_time_stamp_ms_ = 0;
};

}  // namespace surfgrow::scanner
