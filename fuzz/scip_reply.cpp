// Fuzzes scip::parse_reply and what is read from a reply (time stamp, distances in 2 and 3
// characters): the bytes a URG, or anything pretending to be one on the port, sends back.
// scip::ProtocolError is the expected answer to bad bytes; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "surfgrow/scanner/scip.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace scip = surfgrow::scanner::scip;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const scip::Reply r = scip::parse_reply(bytes);
        (void)r.time_stamp();
        (void)r.distances(3);
        (void)r.distances(2);
    } catch (const scip::ProtocolError&) {
    }
    return 0;
}
