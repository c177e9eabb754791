// Writers fill a large buffer and hand it to the stream in few calls (one per megabyte).
#pragma once

#include <charconv>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>

#include "surfgrow/io/scalar_type.hpp"

namespace surfgrow::io {

/// A byte buffer in front of an ostream. Call flush() at the end: the destructor does not, so a
/// writer that throws leaves nothing half-written behind (write_atomically discards it anyway).
class OutputBuffer {
  public:
    explicit OutputBuffer(std::ostream& out, std::size_t capacity = std::size_t{1} << 20)
        : out_(out), capacity_(capacity) {
        buf_.reserve(capacity_ + kSlack);
    }

    void append(std::string_view s) {
        buf_.append(s);
        if (buf_.size() >= capacity_) flush();
    }
    void put(char c) {
        buf_.push_back(c);
        if (buf_.size() >= capacity_) flush();
    }

    /// The value's bytes, reversed when `swap` (big-endian output).
    template <typename T>
    void put_binary(T v, bool swap) {
        if (swap) v = byteswap_value(v);
        char bytes[sizeof(T)];
        std::memcpy(bytes, &v, sizeof(T));
        append(std::string_view(bytes, sizeof(T)));
    }

    /// Shortest decimal text that reads back as the same value ("0.1", "nan", "-inf", "42").
    template <typename T>
    void put_number(T v) {
        char text[kSlack];
        const auto r = std::to_chars(text, text + sizeof text, v);
        append(std::string_view(text, static_cast<std::size_t>(r.ptr - text)));
    }

    /// Hands the buffered bytes to the stream.
    void flush() {
        out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
        buf_.clear();
    }

  private:
    static constexpr std::size_t kSlack = 64;  // longer than any number's text
    std::ostream& out_;
    std::size_t capacity_;
    std::string buf_;
};

}  // namespace surfgrow::io
