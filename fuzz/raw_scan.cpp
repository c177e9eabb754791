// Fuzzes io::decode_raw_scan: the binary raw-scan format (header, readings, truth ids, FNV-1a
// checksum; docs/raw-scan-format.md). A mutated file almost never keeps its checksum, which
// would stop the decoder before the spec, pose and readings; so each input is decoded twice:
// as it is, and with its last 8 bytes replaced by the checksum of the rest.
// A surfgrow::Error is the expected answer to bad input; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/raw_scan_format.hpp"

namespace {

void decode(std::string_view bytes) {
    try {
        (void)surfgrow::io::decode_raw_scan(bytes, "fuzz.sgraw");
    } catch (const surfgrow::Error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    decode(bytes);
    constexpr std::size_t kTrailer = 8;
    if (size < kTrailer) return 0;
    std::string fixed(bytes);
    std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64 of everything before the trailer
    for (std::size_t i = 0; i < size - kTrailer; ++i) {
        h ^= static_cast<unsigned char>(fixed[i]);
        h *= 0x100000001b3ull;
    }
    for (std::size_t i = 0; i < kTrailer; ++i)
        fixed[size - kTrailer + i] = static_cast<char>((h >> (8 * i)) & 0xFF);
    decode(fixed);
    return 0;
}
