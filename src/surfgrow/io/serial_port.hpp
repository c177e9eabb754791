// A serial or USB-ACM port (a URG's /dev/ttyACM0) in raw mode, as the link a UrgDriver talks
// through: write a command, read its reply up to the empty line that ends it.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace surfgrow::io {

class SerialPort {
  public:
    /// Where the first whole reply in the bytes read so far ends, or 0 while it is incomplete.
    /// Empty: SCIP's, the empty line that ends a reply.
    using ReplyEnd = std::function<std::size_t(std::string_view received)>;

    /// Opens `device` raw (8 data bits, no parity, no echo, no line editing) at `baud` (ignored
    /// by USB-ACM sensors; 9600 .. 1000000 for serial ones). Throws Error(kCannotOpen) naming
    /// the device and the system's reason (no such device, permission: the dialout group).
    SerialPort(const std::filesystem::path& device, int baud = 115200,
               std::chrono::milliseconds timeout = std::chrono::milliseconds(1000),
               ReplyEnd reply_end = {});
    ~SerialPort();
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    /// Drops whatever arrived unasked (the tail of a reply given up on), writes `command`, and
    /// returns the bytes up to the reply's end (SCIP: its empty line included); empty when the
    /// time-out passed first. Throws Error(kCannotWrite) when the port fails (the sensor
    /// unplugged).
    [[nodiscard]] std::string exchange(std::string_view command);

  private:
    std::filesystem::path device_;
    std::chrono::milliseconds timeout_;
    ReplyEnd reply_end_;
    int fd_ = -1;
};

}  // namespace surfgrow::io
