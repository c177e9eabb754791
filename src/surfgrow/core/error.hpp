// Errors the library reports to its callers: a category and a message meant for the user.
#pragma once

#include <stdexcept>
#include <string>

namespace surfgrow {

/// Why an operation failed. The numbers are stable: the command line exits with them
/// (README.md, "When something is wrong").
enum class ErrorCode : int {
    kInternal = 1,  ///< a bug: an invariant did not hold
    kUsage = 2,     ///< unknown option, missing argument, bad syntax on the command line
    kInvalidParameter =
        3,               ///< a value out of its valid range (mu <= 0, min_pts < 3, alpha <= 1, ...)
    kCannotOpen = 4,     ///< an input file is missing or unreadable
    kUnknownFormat = 5,  ///< a file whose format surfgrow cannot tell or does not support
    kMalformedInput = 6,  ///< a file that claims a format but breaks it (bad header, truncated)
    kCannotWrite = 7,     ///< an output could not be written (permissions, disk full)
    kCloudTooLarge = 8,   ///< too many points, an extent beyond float range, a grid too wide,
                          ///< or more memory than memory_budget() allows
};

/// Exception carrying an ErrorCode and a message meant for the user. Messages name the file
/// (where there is one) and the problem, and read as one sentence without a trailing period.
class Error : public std::runtime_error {
  public:
    Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    [[nodiscard]] ErrorCode code() const noexcept { return code_; }

  private:
    ErrorCode code_;
};

}  // namespace surfgrow
