#include "surfgrow/scanner/scip.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace surfgrow::scanner::scip {

namespace {

constexpr std::size_t kLineChars = 64;  // data characters per line before its checksum

std::string where(std::string_view echo, std::size_t line) {
    std::string code(echo.substr(0, std::min<std::size_t>(2, echo.size())));
    return (code.empty() ? std::string("reply") : code + " reply") + ", line " +
           std::to_string(line);
}

std::string shown(char c) {
    if (c >= 0x20 && c < 0x7f) return std::string("'") + c + "'";
    return "byte " + std::to_string(static_cast<unsigned char>(c));
}

}  // namespace

char checksum(std::string_view bytes) {
    unsigned sum = 0;
    for (const char c : bytes) sum += static_cast<unsigned char>(c);
    return static_cast<char>((sum & 0x3f) + 0x30);
}

std::string encode(std::uint32_t value, int chars) {
    if (chars < 1 || chars > 5 || (chars < 5 && value >> (6 * chars) != 0))
        throw std::invalid_argument("scip::encode: " + std::to_string(value) + " does not fit in " +
                                    std::to_string(chars) + " characters");
    std::string out(static_cast<std::size_t>(chars), '0');
    for (int k = chars - 1; k >= 0; --k, value >>= 6)
        out[static_cast<std::size_t>(k)] = static_cast<char>((value & 0x3f) + 0x30);
    return out;
}

std::uint32_t decode(std::string_view chars) {
    if (chars.empty() || chars.size() > 5)
        throw ProtocolError("a value of " + std::to_string(chars.size()) + " characters");
    std::uint32_t v = 0;
    for (const char c : chars) {
        if (c < 0x30 || c > 0x6f) throw ProtocolError("value character " + shown(c));
        v = (v << 6) | static_cast<std::uint32_t>(c - 0x30);
    }
    return v;
}

std::string command(std::string_view code, std::string_view tag) {
    const bool tag_ok = tag.size() <= 16 && std::all_of(tag.begin(), tag.end(), [](char c) {
                            return std::isalnum(static_cast<unsigned char>(c)) || c == ' ' ||
                                   c == '.' || c == '_' || c == '+' || c == '@';
                        });
    if (!tag_ok)
        throw std::invalid_argument("scip::command: the tag '" + std::string(tag) +
                                    "' is not up to 16 letters, digits, blanks or . _ + @");
    std::string out(code);
    if (!tag.empty()) out.append(";").append(tag);
    return out + "\n";
}

std::string command(const DistanceRequest& r, std::string_view tag) {
    if (r.first_step < 0 || r.last_step < r.first_step || r.last_step > 9999 || r.cluster < 0 ||
        r.cluster > 99 || r.skip_scans < 0 || r.skip_scans > 9 || r.scans < 0 || r.scans > 99)
        throw std::invalid_argument(
            "scip::command: a distance request out of the protocol's range");
    char buf[32];
    const char* code = r.continuous ? (r.three_chars ? "MD" : "MS") : (r.three_chars ? "GD" : "GS");
    if (r.continuous)
        std::snprintf(buf, sizeof buf, "%s%04d%04d%02d%01d%02d", code, r.first_step, r.last_step,
                      r.cluster, r.skip_scans, r.scans);
    else
        std::snprintf(buf, sizeof buf, "%s%04d%04d%02d", code, r.first_step, r.last_step,
                      r.cluster);
    return command(buf, tag);
}

Reply parse_reply(std::string_view bytes) {
    // Lines up to the empty one that ends the reply.
    std::vector<std::string_view> lines;
    std::size_t at = 0;
    for (;;) {
        const std::size_t lf = bytes.find('\n', at);
        if (lf == std::string_view::npos)
            throw ProtocolError("reply ends without its empty line (" +
                                std::to_string(bytes.size()) + " bytes: cut short?)");
        const std::string_view line = bytes.substr(at, lf - at);
        at = lf + 1;
        if (line.empty()) break;
        lines.push_back(line);
    }
    if (at != bytes.size())
        throw ProtocolError("reply has " + std::to_string(bytes.size() - at) +
                            " bytes after its empty line");
    if (lines.size() < 2) throw ProtocolError("reply without a status line");
    Reply r;
    r.echo = std::string(lines[0]);
    // Status: two characters and their checksum (one-character statuses of old firmware have
    // none).
    const std::string_view status = lines[1];
    if (status.size() == 3) {
        if (checksum(status.substr(0, 2)) != status[2])
            throw ProtocolError(where(r.echo, 2) + ": status checksum " + shown(status[2]) +
                                ", expected " + shown(checksum(status.substr(0, 2))));
        r.status = std::string(status.substr(0, 2));
    } else if (status.size() == 1) {
        r.status = std::string(status);
    } else {
        throw ProtocolError(where(r.echo, 2) + ": a status line of " +
                            std::to_string(status.size()) + " characters");
    }
    const std::string_view code = std::string_view(r.echo).substr(0, 2);
    const bool info_reply = code == "VV" || code == "PP" || code == "II";
    for (std::size_t k = 2; k < lines.size(); ++k) {
        const std::string_view line = lines[k];
        if (line.size() < 2 || line.size() > kLineChars + 1)
            throw ProtocolError(where(r.echo, k + 1) + ": a line of " +
                                std::to_string(line.size()) + " characters");
        const std::string_view text = line.substr(0, line.size() - 1);
        const char sum = line.back();
        const bool info = info_reply && text.back() == ';';
        const bool ok =
            checksum(text) == sum || (info && checksum(text.substr(0, text.size() - 1)) == sum);
        if (!ok)
            throw ProtocolError(where(r.echo, k + 1) + ": checksum " + shown(sum) + ", expected " +
                                shown(checksum(info ? text.substr(0, text.size() - 1) : text)));
        r.lines.emplace_back(text);
    }
    return r;
}

std::string format_reply(std::string_view echo, std::string_view status,
                         std::span<const std::string> lines) {
    const std::string_view code = echo.substr(0, std::min<std::size_t>(2, echo.size()));
    const bool info_reply = code == "VV" || code == "PP" || code == "II";
    std::string out(echo);
    out.append("\n").append(status);
    if (status.size() == 2) out.push_back(checksum(status));
    out.push_back('\n');
    for (const std::string& line : lines) {
        const bool info = info_reply && !line.empty() && line.back() == ';';
        out.append(line);
        out.push_back(checksum(info ? std::string_view(line).substr(0, line.size() - 1) : line));
        out.push_back('\n');
    }
    out.push_back('\n');
    return out;
}

std::vector<std::string> data_lines(std::span<const std::uint32_t> values, int chars) {
    std::string stream;
    stream.reserve(values.size() * static_cast<std::size_t>(chars));
    for (const std::uint32_t v : values) stream += encode(v, chars);
    std::vector<std::string> out;
    for (std::size_t at = 0; at < stream.size(); at += kLineChars)
        out.push_back(stream.substr(at, kLineChars));
    return out;
}

std::uint32_t Reply::time_stamp() const {
    if (lines.empty() || lines[0].size() != 4)
        throw ProtocolError(where(echo, 3) + ": no 4-character time stamp");
    return decode(lines[0]);
}

std::vector<std::uint32_t> Reply::distances(int chars) const {
    std::string stream;
    for (std::size_t k = 1; k < lines.size(); ++k) stream += lines[k];
    const auto c = static_cast<std::size_t>(chars);
    if (chars < 2 || chars > 3 || stream.size() % c != 0)
        throw ProtocolError(where(echo, 4) + ": " + std::to_string(stream.size()) +
                            " data characters are not whole " + std::to_string(chars) +
                            "-character values");
    std::vector<std::uint32_t> out(stream.size() / c);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = decode(std::string_view(stream).substr(i * c, c));
    return out;
}

}  // namespace surfgrow::scanner::scip
