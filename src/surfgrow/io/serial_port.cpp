#include "surfgrow/io/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace {

speed_t speed_of(int baud) {
    switch (baud) {
        case 9600:
            return B9600;
        case 19200:
            return B19200;
        case 38400:
            return B38400;
        case 57600:
            return B57600;
        case 115200:
            return B115200;
        case 230400:
            return B230400;
        case 460800:
            return B460800;
        case 1000000:
            return B1000000;
        default:
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"serial speed ", std::to_string(baud),
                             " is not 9600, 19200, 38400, 57600, 115200, 230400, 460800 or "
                             "1000000"}));
    }
}

}  // namespace

SerialPort::SerialPort(const std::filesystem::path& device, int baud,
                       std::chrono::milliseconds timeout, ReplyEnd reply_end)
    : device_(device), timeout_(timeout), reply_end_(std::move(reply_end)) {
    if (!reply_end_)
        reply_end_ = [](std::string_view in) {
            const std::size_t end = in.find("\n\n");
            return end == std::string_view::npos ? 0 : end + 2;
        };
    const speed_t speed = speed_of(baud);
    fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0)
        throw Error(ErrorCode::kCannotOpen,
                    cat({device.string(), ": ", std::strerror(errno),
                         errno == EACCES ? " (is the user in the dialout group?)" : ""}));
    termios t{};
    if (::tcgetattr(fd_, &t) != 0) {
        const int e = errno;
        ::close(fd_);
        throw Error(ErrorCode::kCannotOpen,
                    cat({device.string(), ": not a serial port (", std::strerror(e), ")"}));
    }
    ::cfmakeraw(&t);
    t.c_cflag |= CLOCAL | CREAD;
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    ::cfsetispeed(&t, speed);
    ::cfsetospeed(&t, speed);
    if (::tcsetattr(fd_, TCSANOW, &t) != 0) {
        const int e = errno;
        ::close(fd_);
        throw Error(ErrorCode::kCannotOpen,
                    cat({device.string(), ": cannot set raw mode (", std::strerror(e), ")"}));
    }
}

SerialPort::~SerialPort() {
    if (fd_ >= 0) ::close(fd_);
}

std::string SerialPort::exchange(std::string_view command) {
    ::tcflush(fd_, TCIFLUSH);
    for (std::size_t at = 0; at < command.size();) {
        const ssize_t n = ::write(fd_, command.data() + at, command.size() - at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throw Error(ErrorCode::kCannotWrite,
                        cat({device_.string(), ": ", std::strerror(errno), " (unplugged?)"}));
        at += static_cast<std::size_t>(n);
    }
    std::string in;
    const auto deadline = std::chrono::steady_clock::now() + timeout_;
    for (;;) {
        const std::size_t end = reply_end_(in);
        if (end != 0) return in.substr(0, end);
        const auto left = std::chrono::ceil<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return {};
        pollfd p{fd_, POLLIN, 0};
        const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
        if (ready < 0 && errno == EINTR) continue;
        if (ready <= 0) return {};
        if (p.revents & (POLLERR | POLLHUP | POLLNVAL)) {
            if (!(p.revents & POLLIN))
                throw Error(ErrorCode::kCannotWrite,
                            cat({device_.string(), ": the port closed (unplugged?)"}));
        }
        char buf[4096];
        const ssize_t n = ::read(fd_, buf, sizeof buf);
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (n <= 0)
            throw Error(ErrorCode::kCannotWrite,
                        cat({device_.string(), ": ",
                             n < 0 ? std::strerror(errno) : "the port closed", " (unplugged?)"}));
        in.append(buf, static_cast<std::size_t>(n));
    }
}

}  // namespace surfgrow::io
