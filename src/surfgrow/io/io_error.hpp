// How the readers report a broken file: Error(kMalformedInput) with the file's name first.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

/// Throws Error(kMalformedInput, "<source>: <what>").
[[noreturn]] inline void throw_malformed(std::string_view source, std::string_view what) {
    throw Error(ErrorCode::kMalformedInput, cat({source, ": ", what}));
}

/// Throws Error(kMalformedInput, "<source> line <n>: <what>").
[[noreturn]] inline void throw_malformed_line(std::string_view source, std::size_t line,
                                              std::string_view what) {
    throw Error(ErrorCode::kMalformedInput,
                cat({source, " line ", std::to_string(line), ": ", what}));
}

/// An integer count as text, for messages.
[[nodiscard]] inline std::string count_str(uint64_t n) {
    return std::to_string(n);
}

/// At most `max` characters of a token, quoted, for messages about bad values; bytes that are
/// not printable ASCII (binary garbage) show as '?'.
[[nodiscard]] inline std::string quoted(std::string_view token, std::size_t max = 40) {
    std::string out = "'";
    for (std::size_t i = 0; i < token.size() && i < max; ++i) {
        const char c = token[i];
        out.push_back(c >= 0x20 && c < 0x7f ? c : '?');
    }
    out.append(token.size() > max ? "...'" : "'");
    return out;
}

/// a * b, or false when it does not fit in 64 bits.
[[nodiscard]] inline bool checked_mul(uint64_t a, uint64_t b, uint64_t& out) {
    return !__builtin_mul_overflow(a, b, &out);
}

/// a + b, or false when it does not fit in 64 bits.
[[nodiscard]] inline bool checked_add(uint64_t a, uint64_t b, uint64_t& out) {
    return !__builtin_add_overflow(a, b, &out);
}

}  // namespace surfgrow::io
