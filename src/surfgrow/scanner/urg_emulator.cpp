#include "surfgrow/scanner/urg_emulator.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <utility>

#include "surfgrow/scanner/scip.hpp"

namespace surfgrow::scanner {

namespace {

constexpr std::uint32_t kScanMs = 100;   // 600 rpm: a scan every 100 ms
constexpr std::uint32_t kMinRange = 20;  // below: the sensor's error codes

bool digits(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c));
    });
}

int number(std::string_view s) {
    int v = 0;
    for (const char c : s) v = v * 10 + (c - '0');
    return v;
}

std::string status_reply(std::string_view echo, std::string_view status) {
    return scip::format_reply(echo, status, {});
}

}  // namespace

UrgEmulator::UrgEmulator(Scan scan, UrgFaults faults)
    : scan_(std::move(scan)), faults_(std::move(faults)) {}

std::string UrgEmulator::distances(std::string_view echo, std::string_view status, int first,
                                   int last, int cluster, int chars) {
    const int index = sent_++;
    std::vector<std::uint32_t> all = scan_();
    all.resize(kSteps, 0);
    clock_ms_ = (clock_ms_ + kScanMs) & 0xffffff;
    if (faults_.dropped.count(index)) return {};
    // A cluster reports its nearest valid reading, or the first one's error code.
    const int group = std::max(cluster, 1);
    std::vector<std::uint32_t> values;
    for (int s = first; s <= last; s += group) {
        std::uint32_t best = all[static_cast<std::size_t>(s)];
        for (int k = s; k < std::min(s + group, last + 1); ++k) {
            const std::uint32_t v = all[static_cast<std::size_t>(k)];
            if (v >= kMinRange && (best < kMinRange || v < best)) best = v;
        }
        values.push_back(chars == 2 ? std::min<std::uint32_t>(best, 4095) : best);
    }
    std::vector<std::string> lines{scip::encode(clock_ms_, 4)};
    for (std::string& l : scip::data_lines(values, chars)) lines.push_back(std::move(l));
    if (faults_.garbled.count(index))  // '~' encodes nothing; format_reply sums it as it is
        for (std::size_t l = 1; l < lines.size(); ++l)
            std::fill(lines[l].begin(), lines[l].end(), '~');
    std::string bytes = scip::format_reply(echo, status, lines);
    if (faults_.corrupt.count(index)) {
        // The last data line's checksum is the byte before its line feed and the final one.
        char& sum = bytes[bytes.size() - 3];
        sum = sum == '0' ? '1' : '0';
    }
    return bytes;
}

std::string UrgEmulator::reply(std::string_view line) {
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
    if (faults_.unplugged_after >= 0 && sent_ >= faults_.unplugged_after) return {};
    const std::string echo(line);
    if (line == "SCIP2.0") return status_reply(echo, "0");
    const std::size_t semicolon = line.find(';');
    const std::string_view body = line.substr(0, semicolon);
    if (semicolon != std::string_view::npos) {
        const std::string_view tag = line.substr(semicolon + 1);
        if (tag.size() > 16) return status_reply(echo, "0G");
        try {
            (void)scip::command("XX", tag);
        } catch (const std::invalid_argument&) {
            return status_reply(echo, "0H");
        }
    }
    const std::string_view code = body.substr(0, std::min<std::size_t>(2, body.size()));
    const std::string_view params = body.substr(code.size());
    if (code == "VV" && params.empty()) {
        const std::vector<std::string> info{
            "VEND:Hokuyo Automatic Co.,Ltd.;", "PROD:SOKUIKI Sensor URG-04LX;",
            "FIRM:3.3.00 (surfgrow emulator);", "PROT:SCIP 2.0;", "SERI:EMULATED;"};
        return scip::format_reply(echo, "00", info);
    }
    if (code == "PP" && params.empty()) {
        const std::vector<std::string> info{"MODL:URG-04LX(Hokuyo Automatic Co.,Ltd.);",
                                            "DMIN:20;",
                                            "DMAX:5600;",
                                            "ARES:1024;",
                                            "AMIN:44;",
                                            "AMAX:725;",
                                            "AFRT:384;",
                                            "SCAN:600;"};
        return scip::format_reply(echo, "00", info);
    }
    if (code == "II" && params.empty()) {
        const std::vector<std::string> info{"MODL:URG-04LX(Hokuyo Automatic Co.,Ltd.);",
                                            std::string("LASR:") + (laser_on_ ? "ON;" : "OFF;"),
                                            "SCSP:600;",
                                            "MESM:Measuring by Normal Mode;",
                                            "SBPS:USB only;",
                                            "TIME:" + scip::encode(clock_ms_, 4) + ";",
                                            "STAT:Sensor is working normally;"};
        return scip::format_reply(echo, "00", info);
    }
    if (code == "BM" && params.empty()) {
        const bool was_on = std::exchange(laser_on_, true);
        return status_reply(echo, was_on ? "02" : "00");
    }
    if (code == "QT" && params.empty()) {
        laser_on_ = false;
        return status_reply(echo, "00");
    }
    if (code == "RS" && params.empty()) {
        laser_on_ = false;
        clock_ms_ = 0;
        return status_reply(echo, "00");
    }
    const bool single = code == "GD" || code == "GS";
    const bool continuous = code == "MD" || code == "MS";
    if (!single && !continuous) return status_reply(echo, "0E");
    if (params.size() != (single ? 10u : 13u)) return status_reply(echo, "0C");
    const char* bad = !digits(params.substr(0, 4))                    ? "01"
                      : !digits(params.substr(4, 4))                  ? "02"
                      : !digits(params.substr(8, 2))                  ? "03"
                      : (continuous && !digits(params.substr(10, 1))) ? "06"
                      : (continuous && !digits(params.substr(11, 2))) ? "07"
                                                                      : nullptr;
    if (bad) return status_reply(echo, bad);
    const int first = number(params.substr(0, 4)), last = number(params.substr(4, 4));
    const int cluster = number(params.substr(8, 2));
    if (last >= kSteps) return status_reply(echo, "04");
    if (last < first) return status_reply(echo, "05");
    const int chars = code[1] == 'D' ? 3 : 2;
    if (single) {
        if (!laser_on_) return status_reply(echo, "10");
        return distances(echo, "00", first, last, cluster, chars);
    }
    // MD/MS: the laser goes on, an acknowledgement, then each scan with the scans still to come
    // in its echo. A count of 0 (until QT) is acknowledged only: an emulator cannot send forever.
    laser_on_ = true;
    const int scans = number(params.substr(11, 2));
    std::string out = status_reply(echo, "00");
    for (int k = scans - 1; k >= 0; --k) {
        if (faults_.unplugged_after >= 0 && sent_ >= faults_.unplugged_after) break;
        const std::string remaining{static_cast<char>('0' + k / 10),
                                    static_cast<char>('0' + k % 10)};
        std::string scan_echo = echo;
        scan_echo.replace(code.size() + 11, 2, remaining);
        out += distances(scan_echo, "99", first, last, cluster, chars);
    }
    return out;
}

}  // namespace surfgrow::scanner
