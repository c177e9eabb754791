// Tilting the scanner: a DYNAMIXEL servo sent to an angle, waited for, and read back.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "surfgrow/scanner/dynamixel.hpp"

namespace surfgrow::scanner::dxl {

/// Sends an instruction packet and returns the status packet's bytes, or nothing after the
/// time-out.
using ServoLink = std::function<std::string(std::string_view packet)>;

/// Tilts a servo and reads back where it went: the angle a scan is stamped with is the servo's
/// own, not the one asked for.
class ServoDriver {
  public:
    ServoDriver(ServoLink link, std::uint8_t id = 1, int attempts = 3, int max_polls = 200);
    /// Pings the servo and enables its torque. Throws ServoError.
    void connect();
    /// Moves to `deg` from the centre, waits until it stops moving, and returns the angle read
    /// back (degrees). Throws ServoError when it does not stop within the polls (stalled).
    double tilt_to(double deg);

    [[nodiscard]] std::uint8_t id() const { return id_; }

  private:
    std::string exchange(std::uint8_t instruction, const std::string& params, const char* what);
    std::uint32_t read(Address a, const char* what);

    ServoLink link_;
    std::uint8_t id_;
    int attempts_, max_polls_;
};

}  // namespace surfgrow::scanner::dxl
