#include "surfgrow/scanner/servo_emulator.hpp"

#include <algorithm>
#include <utility>

namespace surfgrow::scanner::dxl {

namespace {

constexpr std::uint16_t kModelXm430 = 1020;  // XM430-W350's model number

}  // namespace

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
        std::string out = packet(id_, kStatus, std::string(1, static_cast<char>(error)) + data);
        if (faults_.corrupt.count(index)) out.back() = static_cast<char>(out.back() ^ 0x5a);
        return out;
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

}  // namespace surfgrow::scanner::dxl
