#include "surfgrow/scanner/servo_driver.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace surfgrow::scanner::dxl {

namespace {

// The status packet's error byte in words.
std::string what_error(std::uint8_t e) {
    static const char* const kNames[] = {"",
                                         "result fail",
                                         "instruction error",
                                         "CRC error",
                                         "data range error",
                                         "data length error",
                                         "data limit error",
                                         "access error"};
    const std::uint8_t n = e & 0x7f;
    std::string s = n < 8 ? kNames[n] : "error " + std::to_string(n);
    if (e & 0x80) s += std::string(s.empty() ? "" : ", ") + "hardware alert (overload, heat?)";
    return s;
}

}  // namespace

ServoDriver::ServoDriver(ServoLink link, std::uint8_t id, int attempts, int max_polls)
    : link_(std::move(link)),
      id_(id),
      attempts_(std::max(attempts, 1)),
      max_polls_(std::max(max_polls, 1)) {}

std::string ServoDriver::exchange(std::uint8_t instruction, const std::string& params,
                                  const char* what) {
    const std::string name = "servo " + std::to_string(id_);
    std::string problem;
    for (int a = 0; a < attempts_; ++a) {
        const std::string bytes = link_(packet(id_, instruction, params));
        if (bytes.empty()) {
            problem = "time-out";
            continue;
        }
        Packet p;
        try {
            p = parse(bytes);
        } catch (const ServoError& e) {
            problem = e.what();
            continue;
        }
        if (p.id != id_ || p.instruction != kStatus || p.params.empty()) {
            problem = "a packet that is not its status";
            continue;
        }
        const auto error = static_cast<std::uint8_t>(p.params[0]);
        if (error != 0) throw ServoError(name + ": " + what + ": " + what_error(error));
        return p.params.substr(1);
    }
    throw ServoError(
        name + ": no reply to " + what + " in " + std::to_string(attempts_) + " attempts (" +
        problem + ")" +
        (problem == "time-out" ? ": unplugged, another id, or another baud rate?" : ""));
}

std::uint32_t ServoDriver::read(Address a, const char* what) {
    const std::string data = exchange(kRead, le_bytes(a.at, 2) + le_bytes(a.size, 2), what);
    if (data.size() != a.size)
        throw ServoError("servo " + std::to_string(id_) + ": " + what + ": " +
                         std::to_string(data.size()) + " bytes for " + std::to_string(a.size));
    return from_le(data);
}

void ServoDriver::connect() {
    (void)exchange(kPing, {}, "ping");
    (void)exchange(kWrite, le_bytes(kTorqueEnable.at, 2) + std::string(1, '\x01'), "torque on");
}

double ServoDriver::tilt_to(double deg) {
    const std::int32_t goal = ticks_of(deg);
    if (!std::isfinite(deg) || goal < 0 || goal > 4095)
        throw ServoError("servo " + std::to_string(id_) + ": a tilt of " + std::to_string(deg) +
                         " deg is beyond its turn (-180 .. 180 deg from the centre)");
    (void)exchange(kWrite,
                   le_bytes(kGoalPosition.at, 2) + le_bytes(static_cast<std::uint32_t>(goal), 4),
                   "goal position");
    for (int poll = 0; poll < max_polls_; ++poll) {
        if (read(kMoving, "moving") == 0) {
            const auto at = static_cast<std::int32_t>(read(kPresentPosition, "present position"));
            return degrees_of(at);
        }
    }
    const auto at = static_cast<std::int32_t>(read(kPresentPosition, "present position"));
    throw ServoError("servo " + std::to_string(id_) + ": still moving after " +
                     std::to_string(max_polls_) + " polls, at " + std::to_string(degrees_of(at)) +
                     " deg for " + std::to_string(deg) + " (stalled or blocked?)");
}

}  // namespace surfgrow::scanner::dxl
