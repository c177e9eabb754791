// Fuzzes io::parse_planes_ply: the bound planes' mesh, planes.ply.
// A surfgrow::Error is the expected answer to bad input; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/planes_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)surfgrow::io::parse_planes_ply(bytes, "fuzz/planes.ply", surfgrow::Vec3d(1, 2, 3));
    } catch (const surfgrow::Error&) {
    }
    return 0;
}
