// Fuzzes io::parse_poses_file: scan poses, as text rows of 12 or 16 numbers or as JSON.
// A surfgrow::Error is the expected answer to bad input; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/poses_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)surfgrow::io::parse_poses_file(bytes, "fuzz.poses");
    } catch (const surfgrow::Error&) {
    }
    return 0;
}
