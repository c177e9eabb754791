#include "surfgrow/scanner/dynamixel.hpp"

#include <algorithm>
#include <cmath>

namespace surfgrow::scanner::dxl {

namespace {

constexpr char kHeader[] = {'\xff', '\xff', '\xfd', '\x00'};

std::string hex(std::uint8_t b) {
    const char* d = "0123456789ABCDEF";
    return std::string{d[b >> 4], d[b & 15]};
}

}  // namespace

std::int32_t ticks_of(double deg) {
    return 2048 + static_cast<std::int32_t>(std::lround(deg * 4096.0 / 360.0));
}

double degrees_of(std::int32_t ticks) {
    return (ticks - 2048) * 360.0 / 4096.0;
}

std::uint16_t crc16(std::string_view bytes) {
    std::uint16_t crc = 0;
    for (const char c : bytes) {
        crc ^= static_cast<std::uint16_t>(static_cast<std::uint8_t>(c) << 8);
        for (int k = 0; k < 8; ++k)
            crc = static_cast<std::uint16_t>(crc & 0x8000 ? (crc << 1) ^ 0x8005 : crc << 1);
    }
    return crc;
}

std::string le_bytes(std::uint32_t value, int size) {
    std::string out;
    for (int k = 0; k < size; ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xff));
    return out;
}

std::uint32_t from_le(std::string_view bytes) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < bytes.size() && k < 4; ++k)
        v |= std::uint32_t{static_cast<std::uint8_t>(bytes[k])} << (8 * k);
    return v;
}

std::string packet(std::uint8_t id, std::uint8_t instruction, std::string_view params) {
    std::string body{static_cast<char>(instruction)};
    for (const char c : params) {
        body.push_back(c);
        if (body.size() >= 3 && body.compare(body.size() - 3, 3, "\xff\xff\xfd") == 0)
            body.push_back('\xfd');  // byte stuffing: FF FF FD never reads as a header
    }
    std::string out(kHeader, sizeof kHeader);
    out.push_back(static_cast<char>(id));
    out += le_bytes(static_cast<std::uint32_t>(body.size() + 2), 2);
    out += body;
    out += le_bytes(crc16(out), 2);
    return out;
}

std::size_t packet_end(std::string_view bytes) {
    const std::size_t h = bytes.find(std::string_view(kHeader, sizeof kHeader));
    if (h == std::string_view::npos || bytes.size() < h + 7) return 0;
    const std::size_t end = h + 7 + from_le(bytes.substr(h + 5, 2));
    return bytes.size() >= end ? end : 0;
}

Packet parse(std::string_view bytes) {
    if (bytes.size() < 10 || bytes.substr(0, 4) != std::string_view(kHeader, 4))
        throw ServoError("servo packet: no FF FF FD 00 header in " + std::to_string(bytes.size()) +
                         " bytes");
    const std::size_t length = from_le(bytes.substr(5, 2));
    if (bytes.size() != 7 + length || length < 3)
        throw ServoError("servo packet: length " + std::to_string(length) + " for " +
                         std::to_string(bytes.size()) + " bytes");
    const std::uint16_t crc = static_cast<std::uint16_t>(from_le(bytes.substr(bytes.size() - 2)));
    if (crc16(bytes.substr(0, bytes.size() - 2)) != crc)
        throw ServoError("servo packet: CRC " + hex(static_cast<std::uint8_t>(crc >> 8)) +
                         hex(static_cast<std::uint8_t>(crc)) + " does not match its bytes");
    Packet p;
    p.id = static_cast<std::uint8_t>(bytes[4]);
    p.instruction = static_cast<std::uint8_t>(bytes[7]);
    const std::string_view stuffed = bytes.substr(8, length - 3);
    std::string body{static_cast<char>(p.instruction)};
    for (std::size_t k = 0; k < stuffed.size(); ++k) {
        const bool stuffing = stuffed[k] == '\xfd' && body.size() >= 3 &&
                              body.compare(body.size() - 3, 3, "\xff\xff\xfd") == 0;
        if (!stuffing) body.push_back(stuffed[k]);
    }
    p.params = body.substr(1);
    return p;
}

}  // namespace surfgrow::scanner::dxl
