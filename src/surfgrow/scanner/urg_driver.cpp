#include "surfgrow/scanner/urg_driver.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace surfgrow::scanner {

namespace {

// "LABEL:value;" lines as label -> value.
std::map<std::string, std::string> info_of(const scip::Reply& r) {
    std::map<std::string, std::string> out;
    for (const std::string& line : r.lines) {
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos || line.empty() || line.back() != ';') continue;
        out[line.substr(0, colon)] = line.substr(colon + 1, line.size() - colon - 2);
    }
    return out;
}

int integer(const std::map<std::string, std::string>& info, const char* label) {
    const auto it = info.find(label);
    if (it == info.end()) throw DeviceError(std::string("URG: PP lacks ") + label);
    try {
        return std::stoi(it->second);
    } catch (const std::exception&) {
        throw DeviceError(std::string("URG: PP's ") + label + " is not a number: '" + it->second +
                          "'");
    }
}

// What a distance request's status means (SCIP 2.0, GD/GS).
std::string meaning(const std::string& status) {
    if (status == "01" || status == "02" || status == "03")
        return "a step or cluster is not a number";
    if (status == "04") return "the end step is beyond the sensor's";
    if (status == "05") return "the end step is before the start step";
    if (status == "10") return "the laser is off";
    if (status.size() == 2 && status >= "50" && status <= "98")
        return "hardware trouble (laser or motor): the sensor needs attention";
    if (status.size() == 2 && status[0] == '0' && status[1] >= 'A' && status[1] <= 'I')
        return "the sensor did not understand the command";
    return "an unknown status";
}

}  // namespace

UrgDriver::UrgDriver(UrgLink link, int attempts)
    : link_(std::move(link)), attempts_(std::max(attempts, 1)) {}

scip::Reply UrgDriver::request(const std::string& code, bool tagged) {
    std::string problem;
    for (int a = 0; a < attempts_; ++a) {
        if (a > 0) ++retries_;
        const std::string cmd =
            scip::command(code, tagged ? "sg" + std::to_string(next_tag_++ % 100000) : "");
        const std::string bytes = link_(cmd);
        if (bytes.empty()) {
            problem = "time-out";
            continue;
        }
        try {
            scip::Reply r = scip::parse_reply(bytes);
            if (r.echo == std::string_view(cmd).substr(0, cmd.size() - 1)) return r;
            problem = "a reply to another command, " + r.echo;
        } catch (const scip::ProtocolError& e) {
            problem = e.what();
        }
    }
    throw DeviceError(
        "URG: no good reply to " + code + " in " + std::to_string(attempts_) + " attempts (" +
        problem + ")" +
        (problem == "time-out" ? ": unplugged, or another program holds the port?" : ""));
}

UrgIdentity UrgDriver::connect() {
    (void)request("SCIP2.0", false);  // already in SCIP 2.0, a sensor says so by its status
    const scip::Reply vv = request("VV");
    const scip::Reply pp = request("PP");
    for (const scip::Reply* r : {&vv, &pp})
        if (r->status != "00")
            throw DeviceError("URG: " + r->echo.substr(0, 2) + " answered status " + r->status);
    const auto v = info_of(vv), p = info_of(pp);
    UrgIdentity id;
    const auto text = [](const std::map<std::string, std::string>& m, const char* k) {
        const auto it = m.find(k);
        return it == m.end() ? std::string() : it->second;
    };
    id.vendor = text(v, "VEND");
    id.product = text(v, "PROD");
    id.firmware = text(v, "FIRM");
    id.protocol = text(v, "PROT");
    id.serial = text(v, "SERI");
    id.min_mm = integer(p, "DMIN");
    id.max_mm = integer(p, "DMAX");
    id.steps_per_turn = integer(p, "ARES");
    id.first_step = integer(p, "AMIN");
    id.last_step = integer(p, "AMAX");
    id.front_step = integer(p, "AFRT");
    id.rpm = integer(p, "SCAN");
    const std::string bm = request("BM").status;
    if (bm != "00" && bm != "02")
        throw DeviceError("URG: the laser did not go on (BM status " + bm + ")");
    return id;
}

std::vector<std::uint32_t> UrgDriver::scan(int first, int last) {
    scip::DistanceRequest req;
    req.first_step = first;
    req.last_step = last;
    std::string code = scip::command(req);
    code.pop_back();  // the line feed: request() adds the tag and its own
    const auto want = static_cast<std::size_t>(last - first + 1);
    int garbled = 0;
    bool turned_on = false;
    for (;;) {
        const scip::Reply r = request(code);
        if (r.status == "10" && !turned_on) {  // off (a reset, a QT from elsewhere): on again
            turned_on = true;
            (void)request("BM");
            continue;
        }
        if (r.status != "00")
            throw DeviceError("URG: " + code + " answered status " + r.status + ": " +
                              meaning(r.status));
        std::vector<std::uint32_t> mm;
        try {
            mm = r.distances(3);
            last_time_stamp_ms_ = r.time_stamp();
        } catch (const scip::ProtocolError& e) {
            // Sound checksums over values that cannot be: a glitch, asked for again like a
            // damaged reply, within the same attempts.
            if (++garbled >= attempts_)
                throw DeviceError("URG: " + code + ": " + e.what() + " in " +
                                  std::to_string(attempts_) + " attempts");
            ++retries_;
            continue;
        }
        if (mm.size() != want)
            throw DeviceError("URG: " + code + " gave " + std::to_string(mm.size()) +
                              " distances for " + std::to_string(want) + " steps");
        return mm;
    }
}

void UrgDriver::close() {
    const std::string s = request("QT").status;
    if (s != "00") throw DeviceError("URG: QT answered status " + s);
}

}  // namespace surfgrow::scanner
