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
    /// Answers each line written to the port (without its CR/LF) with `device`'s bytes; an
    /// empty answer sends nothing. Throws Error(kCannotOpen) when no pseudo-terminal is free.
    explicit EmulatedPort(std::function<std::string(std::string_view)> device);
    /// Closes the port: a program still using it sees a hang-up, as when a sensor is unplugged.
    ~EmulatedPort();
    EmulatedPort(const EmulatedPort&) = delete;
    EmulatedPort& operator=(const EmulatedPort&) = delete;

    /// The path a program opens (a SerialPort).
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  private:
    void serve();

    std::function<std::string(std::string_view)> device_;
    std::filesystem::path path_;
    int master_ = -1;
    int wake_[2] = {-1, -1};  // written to by the destructor: ends serve()
    std::thread server_;
};

}  // namespace surfgrow::io
