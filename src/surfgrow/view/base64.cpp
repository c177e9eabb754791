#include "surfgrow/view/base64.hpp"

#include <array>
#include <cstdint>

namespace surfgrow::view {

namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

constexpr std::array<std::int8_t, 256> decode_table() {
    std::array<std::int8_t, 256> t{};
    t.fill(-1);
    for (int i = 0; i < 64; ++i) t[static_cast<unsigned char>(kAlphabet[i])] = std::int8_t(i);
    return t;
}

}  // namespace

void append_base64(std::string& out, const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    const std::size_t start = out.size();
    out.resize(start + (size + 2) / 3 * 4);
    char* o = out.data() + start;
    std::size_t i = 0;
    for (; i + 3 <= size; i += 3, o += 4) {
        const std::uint32_t v = std::uint32_t(p[i]) << 16 | std::uint32_t(p[i + 1]) << 8 | p[i + 2];
        o[0] = kAlphabet[v >> 18];
        o[1] = kAlphabet[(v >> 12) & 63];
        o[2] = kAlphabet[(v >> 6) & 63];
        o[3] = kAlphabet[v & 63];
    }
    if (i < size) {
        const bool two = i + 1 < size;
        const std::uint32_t v =
            std::uint32_t(p[i]) << 16 | (two ? std::uint32_t(p[i + 1]) << 8 : 0);
        o[0] = kAlphabet[v >> 18];
        o[1] = kAlphabet[(v >> 12) & 63];
        o[2] = two ? kAlphabet[(v >> 6) & 63] : '=';
        o[3] = '=';
    }
}

std::optional<std::string> decode_base64(std::string_view text) {
    static constexpr auto kTable = decode_table();
    if (text.size() % 4 != 0) return std::nullopt;
    std::string out;
    out.reserve(text.size() / 4 * 3);
    for (std::size_t i = 0; i < text.size(); i += 4) {
        const bool last = i + 4 == text.size();
        std::uint32_t v = 0;
        int pad = 0;
        for (int k = 0; k < 4; ++k) {
            const char c = text[i + static_cast<std::size_t>(k)];
            if (c == '=' && last && k >= 2) {
                ++pad;
                v <<= 6;
                continue;
            }
            const std::int8_t d = kTable[static_cast<unsigned char>(c)];
            if (d < 0 || pad > 0) return std::nullopt;  // bad character, or data after '='
            v = v << 6 | std::uint32_t(d);
        }
        out.push_back(char(v >> 16));
        if (pad < 2) out.push_back(char((v >> 8) & 255));
        if (pad < 1) out.push_back(char(v & 255));
    }
    return out;
}

}  // namespace surfgrow::view
