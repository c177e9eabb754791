// SCIP 2.0, the command protocol of Hokuyo's URG laser range finders (URG-04LX and later), as
// bytes: commands, replies, the character encoding of values and the checksums. No port here:
// a driver writes command() and feeds what it reads to parse_reply().
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace surfgrow::scanner::scip {

/// Bad bytes from a device: what was wrong and where ("GD reply, line 3: checksum 'A', expected
/// 'B'").
class ProtocolError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A line's checksum character: the low 6 bits of the sum of its bytes, plus 0x30 ("00" -> 'P').
[[nodiscard]] char checksum(std::string_view bytes);

/// `value` in `chars` characters of 6 bits each, most significant first, each plus 0x30
/// (1234 in 2 -> "CB", 5432 in 3 -> "1Dh"). Throws std::invalid_argument when it does not fit.
[[nodiscard]] std::string encode(std::uint32_t value, int chars);

/// The value of encoded characters (2: GS/MS distances, 3: GD/MD distances, 4: time stamps).
/// Throws ProtocolError for a character outside 0x30..0x6f.
[[nodiscard]] std::uint32_t decode(std::string_view chars);

/// A distance request: GD/GS (the latest scan, laser on) or MD/MS (`scans` scans, 0 = until QT).
/// Steps are the device's (URG-04LX: 44..725, front at 384); `cluster` merges neighbouring steps.
struct DistanceRequest {
    bool three_chars = true;  ///< GD/MD (18 bits) or GS/MS (12 bits: 4095 mm at most)
    bool continuous = false;  ///< MD/MS
    int first_step = 44;
    int last_step = 725;
    int cluster = 1;
    int skip_scans = 0;  ///< MD/MS: scans skipped between those sent
    int scans = 1;       ///< MD/MS
};

/// The bytes of a command, line feed included, with an optional string echoed in the reply
/// (";tag": up to 16 letters, digits, blanks or . _ + @; it matches a reply to its request).
/// Throws std::invalid_argument for another tag.
[[nodiscard]] std::string command(std::string_view code, std::string_view tag = {});
[[nodiscard]] std::string command(const DistanceRequest& r, std::string_view tag = {});

/// A reply as a device sends it: the echo of the command, a status line and data lines, ended by
/// an empty line. Checksums verified; the lines without their checksums. The information lines
/// of VV, PP and II ("LABEL:value;" and the checksum) are checked over the text before the ';'
/// (the text with it is accepted too: firmware differ) and kept with it.
struct Reply {
    std::string echo;    ///< the command line, tag included, without its line feed
    std::string status;  ///< "00" (done), "99" (MD/MS data), or an error code
    std::vector<std::string> lines;

    /// The distances of a GD/GS/MD/MS reply: the first line is the 4-character time stamp (ms,
    /// 24 bits), the rest one stream of `chars`-character values split in lines of up to 64.
    [[nodiscard]] std::uint32_t time_stamp() const;
    [[nodiscard]] std::vector<std::uint32_t> distances(int chars) const;
};

/// Parses one complete reply (from its echo to the empty line that ends it). Throws
/// ProtocolError naming what is wrong: a missing line feed, a bad checksum, a line too long.
[[nodiscard]] Reply parse_reply(std::string_view bytes);

/// The bytes of a reply (what a device sends): echo, status with checksum, then each line with
/// its checksum (for VV, PP and II over the text before the ';'), then the empty line.
[[nodiscard]] std::string format_reply(std::string_view echo, std::string_view status,
                                       std::span<const std::string> lines);

/// Data lines of values: the stream of encoded values cut into lines of 64 characters (a value
/// may continue on the next line, as the protocol allows).
[[nodiscard]] std::vector<std::string> data_lines(std::span<const std::uint32_t> values, int chars);

}  // namespace surfgrow::scanner::scip
