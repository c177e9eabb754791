// Fuzzes io::read_cloud on bytes in memory read as PCD (ascii, binary, binary_compressed LZF).
// A surfgrow::Error is the expected answer to bad input; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)surfgrow::io::read_cloud(bytes, surfgrow::io::CloudFormat::kPcd, "fuzz.pcd");
    } catch (const surfgrow::Error&) {
    }
    return 0;
}
