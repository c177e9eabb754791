// Wall-clock time of a stage, for the timings results report.
#pragma once

#include <chrono>

namespace surfgrow {

/// Seconds since construction or the last lap(), on the steady clock.
class Stopwatch {
  public:
    /// Seconds since the start.
    [[nodiscard]] double seconds() const {
        return std::chrono::duration<double>(Clock::now() - start_).count();
    }
    /// Seconds since the start, and starts again.
    double lap() {
        const auto now = Clock::now();
        const double s = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return s;
    }

  private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_ = Clock::now();
};

}  // namespace surfgrow
