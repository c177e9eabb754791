// Fuzzes io::detect_format and then io::read_cloud in the format it found, reading points only
// (io::kPointsOnly), as the commands read a cloud whose file name has no known extension.
// A surfgrow::Error is the expected answer to bad input; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfgrow::io;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::optional<CloudFormat> format = detect_format(bytes);
    if (!format) return 0;
    try {
        (void)read_cloud(bytes, *format, "fuzz.cloud", kPointsOnly);
    } catch (const surfgrow::Error&) {
    }
    return 0;
}
