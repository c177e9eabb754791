#include "surfgrow/io/ascii_scan.hpp"

#include <charconv>
#include <cstdlib>
#include <cstring>
#include <system_error>

namespace surfgrow::io {

namespace {

template <typename T>
bool parse_floating(std::string_view token, T& out) {
    const char* b = token.data();
    const char* const e = b + token.size();
    // from_chars rejects the '+' that C's strtod (and many writers) accept.
    if (b != e && *b == '+') {
        ++b;
        if (b != e && (*b == '+' || *b == '-')) return false;
    }
    if (b == e) return false;
    const auto r = std::from_chars(b, e, out);
    if (r.ptr != e) return false;
    if (r.ec == std::errc()) return true;
    if (r.ec != std::errc::result_out_of_range) return false;
    // Overflow or underflow: let strtod pick +-HUGE_VAL or the tiny value it rounds to.
    char buf[128];
    const auto n = static_cast<std::size_t>(e - b);
    if (n >= sizeof buf) return false;
    std::memcpy(buf, b, n);
    buf[n] = '\0';
    if constexpr (sizeof(T) == sizeof(float)) {
        out = std::strtof(buf, nullptr);
    } else {
        out = std::strtod(buf, nullptr);
    }
    return true;
}

}  // namespace

bool parse_double(std::string_view token, double& out) {
    return parse_floating(token, out);
}

bool parse_float(std::string_view token, float& out) {
    return parse_floating(token, out);
}

bool parse_uint(std::string_view token, uint64_t& out) {
    const char* const e = token.data() + token.size();
    const auto r = std::from_chars(token.data(), e, out);
    return !token.empty() && r.ec == std::errc() && r.ptr == e;
}

void split_blanks(std::string_view line, std::vector<std::string_view>& out,
                  std::size_t max_tokens) {
    out.clear();
    std::size_t i = 0;
    const std::size_t n = line.size();
    while (out.size() < max_tokens) {
        while (i < n && is_blank(line[i])) ++i;
        if (i == n) return;
        const std::size_t start = i;
        while (i < n && !is_blank(line[i])) ++i;
        out.push_back(line.substr(start, i - start));
    }
}

bool LineReader::next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const char* start = text_.data() + pos_;
    const std::size_t left = text_.size() - pos_;
    const void* nl = std::memchr(start, '\n', left);
    std::size_t len = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - start) : left;
    pos_ += nl ? len + 1 : len;
    if (len > 0 && start[len - 1] == '\r') --len;
    line = std::string_view(start, len);
    ++next_line_;
    return true;
}

void TokenReader::skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) {
        if (text_[pos_] == '\n') ++line_;
        ++pos_;
    }
}

bool TokenReader::next(std::string_view& token) {
    skip_blanks();
    if (pos_ >= text_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_blank(text_[pos_])) ++pos_;
    token = text_.substr(start, pos_ - start);
    return true;
}

bool TokenReader::at_end() {
    skip_blanks();
    return pos_ >= text_.size();
}

}  // namespace surfgrow::io
