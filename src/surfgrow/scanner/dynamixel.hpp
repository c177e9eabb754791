// The tilt servo's protocol: ROBOTIS DYNAMIXEL Protocol 2.0 packets as bytes (header FF FF FD 00,
// id, length, instruction, parameters with byte stuffing, CRC-16) and the X-series control table
// entries a tilt unit needs.
#pragma once

#include <cstdint>
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

/// Where the first whole packet in `bytes` ends (bytes before its header included), or 0 while
/// it is still incomplete: how a port reading a byte stream cuts it into packets.
[[nodiscard]] std::size_t packet_end(std::string_view bytes);

/// Parses one whole packet. Throws ServoError for a bad header, length or CRC, or bytes left.
[[nodiscard]] Packet parse(std::string_view bytes);

/// Little-endian parameter bytes.
[[nodiscard]] std::string le_bytes(std::uint32_t value, int size);
[[nodiscard]] std::uint32_t from_le(std::string_view bytes);

}  // namespace surfgrow::scanner::dxl
