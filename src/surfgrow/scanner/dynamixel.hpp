// The tilt servo's protocol: ROBOTIS DYNAMIXEL Protocol 2.0 packets as bytes (header FF FF FD 00,
// id, length, instruction, parameters with byte stuffing, CRC-16), the X-series control table
// entries a tilt unit needs, an emulated servo and a driver that tilts and reads back the angle.
#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace surfgrow::scanner::dxl {

/// Bad bytes from a servo, or a servo that reports an error: what, and which packet.
class ServoError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

enum Instruction : std::uint8_t { kPing = 0x01, kRead = 0x02, kWrite = 0x03, kStatus = 0x55 };

/// X-series control table (XM430, XL430, XH430 ...): addresses and sizes in bytes.
struct Address {
    std::uint16_t at;
    std::uint16_t size;
};
inline constexpr Address kTorqueEnable{64, 1};
inline constexpr Address kHardwareError{70, 1};
inline constexpr Address kGoalPosition{116, 4};
inline constexpr Address kMoving{122, 1};
inline constexpr Address kPresentPosition{132, 4};

/// 4096 position ticks per turn, 2048 at the servo's centre: `deg` from the centre and back.
[[nodiscard]] std::int32_t ticks_of(double deg);
[[nodiscard]] double degrees_of(std::int32_t ticks);

/// CRC-16 of the protocol (polynomial 0x8005, initial value 0, not reflected).
[[nodiscard]] std::uint16_t crc16(std::string_view bytes);

/// An instruction packet: header, `id`, length, `instruction`, `params` (FF FF FD in them
/// stuffed to FF FF FD FD), CRC.
[[nodiscard]] std::string packet(std::uint8_t id, std::uint8_t instruction,
                                 std::string_view params = {});

/// A packet read back: id, instruction, parameters unstuffed (for a status packet the first
/// parameter is the error byte).
struct Packet {
    std::uint8_t id = 0;
    std::uint8_t instruction = 0;
    std::string params;
};

/// Parses one whole packet. Throws ServoError for a bad header, length or CRC, or bytes left.
[[nodiscard]] Packet parse(std::string_view bytes);

/// Little-endian parameter bytes.
[[nodiscard]] std::string le_bytes(std::uint32_t value, int size);
[[nodiscard]] std::uint32_t from_le(std::string_view bytes);

/// Faults the emulated servo shows.
struct ServoFaults {
    std::int32_t lag_ticks = 0;  ///< it settles this far from the goal (a loaded or worn gear)
    std::int32_t stall_at = -1;  ///< it cannot pass this position: stops there, moving forever
    std::set<int> dropped;       ///< these status packets (counted from 0) are never sent
};

/// An X-series servo as its packets show it: goal, present position moving towards the goal by
/// `ticks_per_poll` every time it is asked whether it moves (time passes as the driver polls).
class ServoEmulator {
  public:
    explicit ServoEmulator(std::uint8_t id = 1, std::int32_t ticks_per_poll = 40,
                           ServoFaults faults = {});
    /// The status packet answering `instruction` bytes; empty for another id or a dropped one.
    [[nodiscard]] std::string reply(std::string_view instruction);
    [[nodiscard]] std::int32_t position() const { return position_; }

  private:
    std::uint8_t id_;
    std::int32_t step_;
    ServoFaults faults_;
    std::int32_t goal_ = 2048, position_ = 2048;
    bool torque_ = false;
    int sent_ = 0;
};

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

  private:
    std::string exchange(std::uint8_t instruction, const std::string& params, const char* what);
    std::uint32_t read(Address a, const char* what);

    ServoLink link_;
    std::uint8_t id_;
    int attempts_, max_polls_;
};

}  // namespace surfgrow::scanner::dxl
