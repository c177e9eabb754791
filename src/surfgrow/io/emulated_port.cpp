#include "surfgrow/io/emulated_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace {

[[noreturn]] void no_pty(const char* step) {
    throw Error(ErrorCode::kCannotOpen,
                cat({"emulated port: ", step, " failed (", std::strerror(errno), ")"}));
}

}  // namespace

EmulatedPort::EmulatedPort(std::function<std::string(std::string_view)> device,
                           RequestEnd request_end)
    : device_(std::move(device)), request_end_(std::move(request_end)) {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master_ < 0) no_pty("posix_openpt");
    char name[128];
    if (::grantpt(master_) != 0 || ::unlockpt(master_) != 0 ||
        ::ptsname_r(master_, name, sizeof name) != 0) {
        ::close(master_);
        no_pty("unlocking the pseudo-terminal");
    }
    if (::pipe2(wake_, O_CLOEXEC) != 0) {
        ::close(master_);
        no_pty("pipe");
    }
    path_ = name;
    server_ = std::thread([this] { serve(); });
}

EmulatedPort::~EmulatedPort() {
    const char stop = 1;
    (void)!::write(wake_[1], &stop, 1);
    server_.join();
    ::close(master_);
    ::close(wake_[0]);
    ::close(wake_[1]);
}

void EmulatedPort::serve() {
    std::string line;
    for (;;) {
        pollfd p[2] = {{master_, POLLIN, 0}, {wake_[0], POLLIN, 0}};
        if (::poll(p, 2, -1) < 0) {
            if (errno == EINTR) continue;
            return;
        }
        if (p[1].revents) return;
        if (p[0].revents & POLLHUP) {  // nobody has the port open: wait for a program
            ::usleep(1000);
            continue;
        }
        char buf[256];
        const ssize_t n = ::read(master_, buf, sizeof buf);
        if (n < 0 && (errno == EINTR || errno == EAGAIN || errno == EIO)) {
            ::usleep(1000);  // EIO: the program closed the port; another may open it
            continue;
        }
        if (n <= 0) return;
        if (request_end_) {
            line.append(buf, static_cast<std::size_t>(n));
            for (std::size_t end; (end = request_end_(line)) != 0;) {
                answer(std::string_view(line).substr(0, end));
                line.erase(0, end);
            }
            if (line.size() > 65536) line.clear();  // no request in sight: noise
            continue;
        }
        for (ssize_t k = 0; k < n; ++k) {
            const char c = buf[k];
            if (c != '\n' && c != '\r') {
                line.push_back(c);
                continue;
            }
            if (line.empty()) continue;  // the LF of a CR LF
            answer(line);
            line.clear();
        }
    }
}

void EmulatedPort::answer(std::string_view request) {
    const std::string reply = device_(request);
    for (std::size_t at = 0; at < reply.size();) {
        const ssize_t w = ::write(master_, reply.data() + at, reply.size() - at);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) break;
        at += static_cast<std::size_t>(w);
    }
}

}  // namespace surfgrow::io
