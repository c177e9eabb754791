#include "surfgrow/scanner/dynamixel.hpp"

#include <algorithm>
#include <cmath>

namespace surfgrow::scanner::dxl {

namespace {

constexpr char kHeader[] = {'\xff', '\xff', '\xfd', '\x00'};
constexpr std::uint16_t kModelXm430 = 1020;  // XM430-W350's model number

std::string hex(std::uint8_t b) {
    const char* d = "0123456789ABCDEF";
    return std::string{d[b >> 4], d[b & 15]};
}

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

ServoEmulator::ServoEmulator(std::uint8_t id, std::int32_t ticks_per_poll, ServoFaults faults)
    : id_(id), step_(std::max(ticks_per_poll, 1)), faults_(std::move(faults)) {}

std::string ServoEmulator::reply(std::string_view instruction) {
    Packet in;
    try {
        in = parse(instruction);
    } catch (const ServoError&) {
        return {};  // a damaged packet is not answered
    }
    if (in.id != id_) return {};
    const int index = sent_++;
    if (faults_.dropped.count(index)) return {};
    const auto status = [&](std::uint8_t error, const std::string& data = {}) {
        return packet(id_, kStatus, std::string(1, static_cast<char>(error)) + data);
    };
    const std::int32_t target = std::clamp(goal_ + faults_.lag_ticks, 0, 4095);
    const bool stalled = position_ == faults_.stall_at && target != position_;
    switch (in.instruction) {
        case kPing:
            return status(0, le_bytes(kModelXm430, 2) + std::string(1, '\x2d'));
        case kRead: {
            if (in.params.size() != 4) return status(5);
            const auto at = static_cast<std::uint16_t>(from_le(in.params.substr(0, 2)));
            const auto size = static_cast<int>(from_le(in.params.substr(2, 2)));
            if (at == kMoving.at) {  // time passes while the driver waits
                if (torque_ && !stalled && position_ != target) {
                    const std::int32_t d = std::clamp(target - position_, -step_, step_);
                    std::int32_t next = position_ + d;
                    if (faults_.stall_at >= 0 && std::min(position_, next) <= faults_.stall_at &&
                        faults_.stall_at <= std::max(position_, next))
                        next = faults_.stall_at;
                    position_ = next;
                }
                return status(0, le_bytes(position_ != target ? 1 : 0, size));
            }
            if (at == kPresentPosition.at) return status(0, le_bytes(position_, size));
            if (at == kGoalPosition.at) return status(0, le_bytes(goal_, size));
            if (at == kTorqueEnable.at) return status(0, le_bytes(torque_, size));
            if (at == kHardwareError.at) return status(0, le_bytes(stalled ? 0x20 : 0, size));
            return status(4);
        }
        case kWrite: {
            if (in.params.size() < 3) return status(5);
            const auto at = static_cast<std::uint16_t>(from_le(in.params.substr(0, 2)));
            const std::string_view data = std::string_view(in.params).substr(2);
            if (at == kTorqueEnable.at && data.size() == 1) {
                torque_ = data[0] != 0;
                return status(0);
            }
            if (at == kGoalPosition.at && data.size() == 4) {
                const auto goal = static_cast<std::int32_t>(from_le(data));
                if (goal < 0 || goal > 4095) return status(6);  // data limit
                goal_ = goal;
                return status(0);
            }
            return status(7);  // access error: not writable here
        }
        default:
            return status(2);
    }
}

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
