#include "surfgrow/io/file_bytes.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/memory_budget.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace {

[[noreturn]] void cannot_open(const std::filesystem::path& path, std::string_view why) {
    throw Error(ErrorCode::kCannotOpen, cat({"cannot open ", path.string(), ": ", why}));
}

std::string_view open_error(int err) {
    switch (err) {
        case ENOENT:
            return "no such file";
        case EACCES:
        case EPERM:
            return "permission denied";
        default:
            return std::strerror(err);
    }
}

// Closes the descriptor on every path out of read().
struct Fd {
    int fd;
    ~Fd() { ::close(fd); }
};

// read() until `size` bytes or end of file; returns the bytes read.
std::size_t read_fully(int fd, char* buf, std::size_t size, const std::filesystem::path& path) {
    std::size_t got = 0;
    while (got < size) {
        const ssize_t r = ::read(fd, buf + got, size - got);
        if (r == 0) break;
        if (r < 0) {
            if (errno == EINTR) continue;
            cannot_open(path, cat({"read failed: ", std::strerror(errno)}));
        }
        got += static_cast<std::size_t>(r);
    }
    return got;
}

}  // namespace

FileBytes FileBytes::read(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) cannot_open(path, open_error(errno));
    const Fd guard{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) cannot_open(path, std::strerror(errno));
    if (S_ISDIR(st.st_mode)) cannot_open(path, "it is a folder, not a file");

    FileBytes out;
    // Files in /proc and the like report size 0: read those as a stream.
    if (S_ISREG(st.st_mode) && st.st_size > 0) {
        // One read() of the size fstat reports; a file that shrinks meanwhile is read as it is.
        const auto size = static_cast<std::size_t>(st.st_size);
        check_memory(double(size),
                     cat({path.string(), ": reading its ", std::to_string(size / 1000000), " MB"}));
        out.data_ = std::make_unique_for_overwrite<char[]>(size);
        out.size_ = read_fully(fd, out.data_.get(), size, path);
        return out;
    }
    // A pipe, a device or a /proc file: its size is unknown, so grow the buffer by doubling.
    std::size_t capacity = 1 << 16;
    out.data_ = std::make_unique_for_overwrite<char[]>(capacity);
    while (true) {
        const std::size_t got =
            read_fully(fd, out.data_.get() + out.size_, capacity - out.size_, path);
        out.size_ += got;
        if (out.size_ < capacity) return out;
        check_memory(double(capacity) * 2, cat({path.string(), ": reading more than ",
                                                std::to_string(capacity / 1000000), " MB"}));
        auto bigger = std::make_unique_for_overwrite<char[]>(capacity * 2);
        std::memcpy(bigger.get(), out.data_.get(), out.size_);
        out.data_ = std::move(bigger);
        capacity *= 2;
    }
}

}  // namespace surfgrow::io
