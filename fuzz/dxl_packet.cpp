// Fuzzes the DYNAMIXEL Protocol 2.0 packet reader (dxl::packet_end, dxl::parse): the bytes a
// servo, or noise on its bus, sends back. dxl::ServoError is the expected answer to bad bytes;
// anything else escaping is a finding. The packet is also cut where packet_end says, as a port
// reading a byte stream does.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "surfgrow/scanner/dynamixel.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace dxl = surfgrow::scanner::dxl;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (const std::string_view b : {bytes, bytes.substr(0, dxl::packet_end(bytes))}) {
        try {
            const dxl::Packet p = dxl::parse(b);
            if (p.params.size() >= 4) (void)dxl::from_le(std::string_view(p.params).substr(0, 4));
        } catch (const dxl::ServoError&) {
        }
    }
    return 0;
}
