// Fuzzes io::parse_labels_bin: a result folder's labels.bin.
// A surfgrow::Error is the expected answer to bad input; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/results_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)surfgrow::io::parse_labels_bin(bytes, "fuzz/labels.bin");
    } catch (const surfgrow::Error&) {
    }
    return 0;
}
