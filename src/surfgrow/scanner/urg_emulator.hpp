// A URG-04LX as its SCIP 2.0 replies see it, fed by a range function (the simulator, a test):
// what a driver talks to when there is no sensor, with faults on demand.
#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace surfgrow::scanner {

/// Faults the emulator injects into its distance replies (GD/GS, and each scan of MD/MS),
/// counted from 0 in the order it sends them.
struct UrgFaults {
    std::set<int> corrupt;  ///< these replies get a wrong checksum on their last data line
    std::set<int> dropped;  ///< these replies are never sent (a time-out for the driver)
    /// These replies are malformed with sound checksums: their data characters lie outside the
    /// encoding (a firmware or line glitch the checksum does not catch).
    std::set<int> garbled;
    int unplugged_after = -1;  ///< after this many distance replies, nothing at all is sent
};

class UrgEmulator {
  public:
    /// Distances in mm of every step 0..768 of one scan (URG-04LX: 0 for no echo, values below
    /// 20 are the sensor's error codes); called once per scan sent.
    using Scan = std::function<std::vector<std::uint32_t>()>;

    static constexpr int kSteps = 769;  ///< steps 0..768; 44..725 measure, 384 is the front
    static constexpr int kFirstStep = 44, kLastStep = 725, kFrontStep = 384;

    explicit UrgEmulator(Scan scan, UrgFaults faults = {});

    /// The bytes the sensor sends for one command line (CR, LF or both after it are ignored):
    /// empty when it sends nothing (a dropped reply, or unplugged). MD/MS give their
    /// acknowledgement and then every scan asked for.
    [[nodiscard]] std::string reply(std::string_view command_line);

    [[nodiscard]] bool laser_on() const { return laser_on_; }

  private:
    std::string distances(std::string_view echo, std::string_view status, int first, int last,
                          int cluster, int chars);

    Scan scan_;
    UrgFaults faults_;
    bool laser_on_ = false;
    int sent_ = 0;                // distance replies counted so far (sent or not)
    std::uint32_t clock_ms_ = 0;  // the sensor's 24-bit time stamp
};

}  // namespace surfgrow::scanner
