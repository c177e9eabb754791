// An X-series DYNAMIXEL servo as its status packets show it: what the tilt driver talks to when
// there is no servo, with lag, a stall and lost packets on demand.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "surfgrow/scanner/dynamixel.hpp"

namespace surfgrow::scanner::dxl {

/// Faults the emulated servo shows.
struct ServoFaults {
    std::int32_t lag_ticks = 0;  ///< it settles this far from the goal (a loaded or worn gear)
    std::int32_t stall_at = -1;  ///< it cannot pass this position: stops there, moving forever
    std::set<int> dropped;       ///< these status packets (counted from 0) are never sent
    std::set<int> corrupt;       ///< these status packets arrive with a wrong CRC
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

}  // namespace surfgrow::scanner::dxl
