// The surfgrow command's exit statuses (README.md, "When something is wrong"): the library's error
// codes, one for one, and the outcomes only the command has.
#pragma once

#include <stdexcept>
#include <string>

#include "surfgrow/core/error.hpp"

namespace surfgrow::cli {

/// The outcomes of a command that ran as asked but must not report success to a script.
enum class Outcome : int {
    /// A bound given to `eval --require` (or `demo`) does not hold; the evaluation is written.
    kRequirementFailed = 9,
    kCollision = 10,  ///< `collide --fail-on-collision`: a robot link is too close
    /// `acquire`: the sensor or the servo failed (no reply, damaged replies, stalled); what was
    /// taken before is written, marked partial.
    kDeviceFailed = 11,
};

/// Thrown by a command for an Outcome, with the message it prints.
class OutcomeError : public std::runtime_error {
  public:
    OutcomeError(Outcome outcome, const std::string& message)
        : std::runtime_error(message), outcome_(outcome) {}
    [[nodiscard]] Outcome outcome() const noexcept { return outcome_; }

  private:
    Outcome outcome_;
};

/// The exit status of a library error: its code's number (1 to 8).
[[nodiscard]] inline int exit_status(ErrorCode code) {
    return static_cast<int>(code);
}
[[nodiscard]] inline int exit_status(Outcome outcome) {
    return static_cast<int>(outcome);
}

}  // namespace surfgrow::cli
