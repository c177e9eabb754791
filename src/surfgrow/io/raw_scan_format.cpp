#include "surfgrow/io/raw_scan_format.hpp"

#include <array>
#include <bit>
#include <cstring>
#include <ostream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/scan_files_common.hpp"
#include "surfgrow/scanner/pose.hpp"

namespace surfgrow::io {

namespace {

constexpr std::array<char, 8> kMagic = {'S', 'G', 'R', 'A', 'W', 'S', 'C', 'N'};
constexpr std::uint32_t kFlagTruth = 1;
constexpr std::uint32_t kFlagTiltRead = 2;  // version 2 on
constexpr std::uint32_t kFlagTimes = 4;     // version 2 on
constexpr std::uint32_t kFlagPlanned = 8;   // version 2 on
constexpr std::uint32_t kFlagText = 16;     // version 2 on
constexpr std::uint32_t kFlagsV1 = kFlagTruth;
constexpr std::uint32_t kFlagsV2 =
    kFlagTruth | kFlagTiltRead | kFlagTimes | kFlagPlanned | kFlagText;
constexpr std::size_t kTrailerBytes = 8;

// FNV-1a, 64 bit: simple, fully specified, catches flipped bits and shuffled blocks.
std::uint64_t fnv1a(std::string_view bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ull;
    }
    return h;
}

// Little-endian writer.
class Writer {
  public:
    explicit Writer(std::size_t reserve) { buf_.reserve(reserve); }
    void raw(const char* p, std::size_t n) { buf_.append(p, n); }
    void u(std::uint64_t v, int bytes) {
        for (int i = 0; i < bytes; ++i) buf_.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
    }
    void i32(std::int32_t v) { u(static_cast<std::uint32_t>(v), 4); }
    void f64(double v) { u(std::bit_cast<std::uint64_t>(v), 8); }
    std::string& bytes() { return buf_; }

  private:
    std::string buf_;
};

// Little-endian reader over bytes whose size has already been checked.
class Reader {
  public:
    explicit Reader(std::string_view bytes) : b_(bytes) {}
    std::uint64_t u(int bytes) {
        std::uint64_t v = 0;
        for (int i = 0; i < bytes; ++i)
            v |= std::uint64_t{static_cast<unsigned char>(b_[pos_ + i])} << (8 * i);
        pos_ += static_cast<std::size_t>(bytes);
        return v;
    }
    std::int32_t i32() { return static_cast<std::int32_t>(static_cast<std::uint32_t>(u(4))); }
    double f64() { return std::bit_cast<double>(u(8)); }
    std::string text(std::size_t n) {
        std::string t(b_.substr(pos_, n));
        pos_ += n;
        return t;
    }
    [[nodiscard]] std::size_t pos() const { return pos_; }

  private:
    std::string_view b_;
    std::size_t pos_ = 0;
};

}  // namespace

std::string encode_raw_scan(const scanner::RawScan& scan) {
    scan.validate();
    const scanner::ScannerSpec& s = scan.spec;
    const bool text = !scan.note.empty() || !scan.stop_reason.empty();
    const std::uint32_t flags =
        (scan.has_truth() ? kFlagTruth : 0) | (scan.tilt_read_deg.empty() ? 0 : kFlagTiltRead) |
        (scan.sensor_time_ms.empty() ? 0 : kFlagTimes) |
        (scan.planned_positions == 0 ? 0 : kFlagPlanned) | (text ? kFlagText : 0);
    const std::size_t total = kRawScanHeaderBytes + 2 * scan.readings_mm.size() +
                              4 * scan.truth_face_id.size() + 8 * scan.tilt_read_deg.size() +
                              4 * scan.sensor_time_ms.size() + 4 + 8 + scan.note.size() +
                              scan.stop_reason.size() + kTrailerBytes;
    Writer w(total);
    w.raw(kMagic.data(), kMagic.size());
    w.u((flags & ~kFlagsV1) == 0 ? 1 : kRawScanVersion, 4);
    w.u(flags, 4);
    w.f64(s.laser.step_deg);
    w.i32(s.laser.first_step);
    w.i32(s.laser.last_step);
    w.i32(s.laser.front_step);
    w.i32(s.laser.first_detect_step);
    w.i32(s.laser.last_detect_step);
    w.u(s.laser.min_range_mm, 2);
    w.u(s.laser.max_range_mm, 2);
    w.f64(s.laser.beam_divergence_deg);
    w.f64(s.tilt.first_deg);
    w.f64(s.tilt.step_deg);
    w.i32(s.tilt.positions);
    w.i32(s.readings_per_ray);
    for (int i = 0; i < 3; ++i) w.f64(s.optical_offset_m[i]);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) w.f64(scan.pose.matrix()(r, c));
    w.u(scan.readings_mm.size(), 8);
    for (const std::uint16_t v : scan.readings_mm) w.u(v, 2);
    for (const std::int32_t id : scan.truth_face_id) w.i32(id);
    for (const double deg : scan.tilt_read_deg) w.f64(deg);
    for (const std::uint32_t ms : scan.sensor_time_ms) w.u(ms, 4);
    if (flags & kFlagPlanned) w.u(static_cast<std::uint32_t>(scan.planned_positions), 4);
    if (flags & kFlagText)
        for (const std::string* t : {&scan.note, &scan.stop_reason}) {
            w.u(t->size(), 4);
            w.raw(t->data(), t->size());
        }
    w.u(fnv1a(w.bytes()), 8);
    return std::move(w.bytes());
}

scanner::RawScan decode_raw_scan(std::string_view bytes, std::string_view name) {
    using detail::malformed;
    if (bytes.size() < kRawScanHeaderBytes + kTrailerBytes)
        malformed(name, cat({"truncated raw scan: ", std::to_string(bytes.size()),
                             " bytes, the header alone needs ",
                             std::to_string(kRawScanHeaderBytes + kTrailerBytes)}));
    if (std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0)
        malformed(name, "not a surfgrow raw scan (bad magic; expected SGRAWSCN)");
    Reader r(bytes.substr(kMagic.size()));
    const auto version = r.u(4);
    if (version < 1 || version > kRawScanVersion)
        malformed(name, cat({"unsupported raw-scan version ", std::to_string(version),
                             " (this surfgrow reads versions 1 and 2)"}));
    const auto flags = r.u(4);
    if ((flags & ~std::uint64_t{version == 1 ? kFlagsV1 : kFlagsV2}) != 0)
        malformed(name, cat({"unknown raw-scan flags ", std::to_string(flags), " for version ",
                             std::to_string(version)}));

    scanner::RawScan scan;
    scanner::ScannerSpec& s = scan.spec;
    s.laser.step_deg = r.f64();
    s.laser.first_step = r.i32();
    s.laser.last_step = r.i32();
    s.laser.front_step = r.i32();
    s.laser.first_detect_step = r.i32();
    s.laser.last_detect_step = r.i32();
    s.laser.min_range_mm = static_cast<std::uint16_t>(r.u(2));
    s.laser.max_range_mm = static_cast<std::uint16_t>(r.u(2));
    s.laser.beam_divergence_deg = r.f64();
    s.tilt.first_deg = r.f64();
    s.tilt.step_deg = r.f64();
    s.tilt.positions = r.i32();
    s.readings_per_ray = r.i32();
    for (int i = 0; i < 3; ++i) s.optical_offset_m[i] = r.f64();
    Eigen::Matrix4d m;
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c) m(row, c) = r.f64();
    const std::uint64_t count = r.u(8);

    // Sizes from the header, bounded before any arithmetic can overflow or allocate.
    const std::int64_t steps = std::int64_t{s.laser.last_step} - s.laser.first_step + 1;
    if (steps < 1 || steps > 8192 || s.tilt.positions < 1 || s.tilt.positions > 20000 ||
        s.readings_per_ray < 1 || s.readings_per_ray > 255)
        malformed(name, cat({"implausible header: ", std::to_string(s.tilt.positions), " tilts x ",
                             std::to_string(steps), " steps x ", std::to_string(s.readings_per_ray),
                             " readings"}));
    const auto rays = static_cast<std::uint64_t>(steps) * std::uint64_t(s.tilt.positions);
    const std::uint64_t readings = rays * std::uint64_t(s.readings_per_ray);
    if (count != readings)
        malformed(name, cat({"header says ", std::to_string(count), " readings but its spec needs ",
                             std::to_string(readings)}));
    const auto positions = static_cast<std::uint64_t>(s.tilt.positions);
    const std::uint64_t fixed =
        kRawScanHeaderBytes + 2 * readings + ((flags & kFlagTruth) ? 4 * rays : 0) +
        ((flags & kFlagTiltRead) ? 8 * positions : 0) + ((flags & kFlagTimes) ? 4 * positions : 0) +
        ((flags & kFlagPlanned) ? 4 : 0);
    // The two texts' lengths sit after the fixed part: read them where the file holds them.
    std::uint64_t text_bytes = 0;
    if (flags & kFlagText) {
        for (int t = 0; t < 2; ++t) {
            const std::uint64_t at = fixed + 4 * t + text_bytes;
            if (bytes.size() < at + 4 + kTrailerBytes)
                malformed(name, cat({"truncated raw scan: ", std::to_string(bytes.size()),
                                     " bytes, its text needs more"}));
            const std::uint64_t len = Reader(bytes.substr(at)).u(4);
            if (len > scanner::kMaxRawScanNoteBytes)
                malformed(name, cat({"raw-scan text of ", std::to_string(len), " bytes (at most ",
                                     std::to_string(scanner::kMaxRawScanNoteBytes), ")"}));
            text_bytes += len;
        }
        text_bytes += 8;
    }
    const std::uint64_t expected = fixed + text_bytes + kTrailerBytes;
    if (bytes.size() != expected)
        malformed(name, cat({bytes.size() < expected ? "truncated raw scan: " : "raw scan has ",
                             std::to_string(bytes.size()), " bytes where its header needs ",
                             std::to_string(expected)}));
    const std::string_view body = bytes.substr(0, bytes.size() - kTrailerBytes);
    if (Reader(bytes.substr(body.size())).u(8) != fnv1a(body))
        malformed(name, "checksum mismatch (the file is corrupted)");

    try {
        s.validate();
        scan.pose = scanner::rigid_from_matrix(m);
    } catch (const Error& e) {
        detail::rethrow_in(name, e);
    }
    Reader data(bytes.substr(kRawScanHeaderBytes));
    scan.readings_mm.resize(readings);
    for (auto& v : scan.readings_mm) v = static_cast<std::uint16_t>(data.u(2));
    if (flags & kFlagTruth) {
        scan.truth_face_id.resize(rays);
        for (auto& id : scan.truth_face_id) {
            id = data.i32();
            if (id < -1)
                malformed(name, cat({"ground-truth face id ", std::to_string(id), " < -1"}));
        }
    }
    if (flags & kFlagTiltRead) {
        scan.tilt_read_deg.resize(positions);
        for (auto& deg : scan.tilt_read_deg) deg = data.f64();
    }
    if (flags & kFlagTimes) {
        scan.sensor_time_ms.resize(positions);
        for (auto& ms : scan.sensor_time_ms) ms = static_cast<std::uint32_t>(data.u(4));
    }
    if (flags & kFlagPlanned) scan.planned_positions = static_cast<int>(data.u(4));
    if (flags & kFlagText) {
        scan.note = data.text(data.u(4));
        scan.stop_reason = data.text(data.u(4));
    }
    try {
        scan.validate();  // the read-back angles and the plan
    } catch (const Error& e) {
        detail::rethrow_in(name, e);
    }
    return scan;
}

void write_raw_scan(const std::filesystem::path& path, const scanner::RawScan& scan) {
    std::string bytes;
    try {
        bytes = encode_raw_scan(scan);
    } catch (const Error& e) {
        detail::rethrow_in(path.string(), e);
    }
    write_atomically(path, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

scanner::RawScan read_raw_scan(const std::filesystem::path& path) {
    // The largest valid file: 2^28 readings, their truth ids, 20000 positions' angles and time
    // stamps, the plan and two texts.
    constexpr std::size_t kMaxBytes = kRawScanHeaderBytes + 2 * scanner::kMaxReadingsPerScan +
                                      4 * scanner::kMaxReadingsPerScan + 12 * 20000 + 4 + 8 +
                                      2 * scanner::kMaxRawScanNoteBytes + kTrailerBytes;
    const std::string bytes = detail::read_file_capped(path, kMaxBytes, "a raw scan");
    return decode_raw_scan(bytes, path.string());
}

}  // namespace surfgrow::io
