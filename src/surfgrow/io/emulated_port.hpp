// A device behind a pseudo-terminal: what a program opens as a serial port (/dev/pts/N) is
// answered by a function, line by line. The URG emulator goes behind one for tests and demos, so
// the driver's whole path (open, raw mode, write, poll, read) is the one a real sensor meets.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <thread>

namespace surfgrow::io {

class EmulatedPort {
  public:
    /// Where the first whole request in the bytes written so far ends, or 0 while incomplete.
    using RequestEnd = std::function<std::size_t(std::string_view pending)>;

    /// Answers each request written to the port with `device`'s bytes; an empty answer sends
    /// nothing. Without `request_end` a request is a line, passed without its CR/LF (SCIP);
    /// with it, the request's bytes as written (a servo's packets). Throws Error(kCannotOpen)
    /// when no pseudo-terminal is free.
    explicit EmulatedPort(std::function<std::string(std::string_view)> device,
                          RequestEnd request_end = {});
    /// Closes the port: a program still using it sees a hang-up, as when a sensor is unplugged.
    ~EmulatedPort();
    EmulatedPort(const EmulatedPort&) = delete;
    EmulatedPort& operator=(const EmulatedPort&) = delete;

    /// The path a program opens (a SerialPort).
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  private:
    void serve();

    void answer(std::string_view request);

    std::function<std::string(std::string_view)> device_;
    RequestEnd request_end_;
    std::filesystem::path path_;
    int master_ = -1;
    int wake_[2] = {-1, -1};  // written to by the destructor: ends serve()
    std::thread server_;
};

}  // namespace surfgrow::io
