#include "surfgrow/io/fixed_ply_header.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "surfgrow/core/text.hpp"
#include "surfgrow/io/io_error.hpp"

namespace surfgrow::io {

FixedPlyHeader read_fixed_ply_header(std::string_view all, std::string_view source) {
    constexpr std::string_view kEnd = "end_header\n";
    const std::size_t end = all.find(kEnd);
    if (all.substr(0, 4) != "ply\n" || end == std::string_view::npos)
        throw_malformed(source, "not a PLY file (no \"ply\" line or no end_header)");
    FixedPlyHeader h;
    h.body = end + kEnd.size();
    std::istringstream head{std::string(all.substr(0, end))};
    std::string line;
    while (std::getline(head, line)) {
        std::istringstream ls(line);
        std::string word;
        ls >> word;
        if (word == "format") {
            std::string encoding;
            ls >> encoding;
            h.binary_little_endian = encoding == "binary_little_endian";
        } else if (word == "comment") {
            std::string key;
            ls >> key;
            if (key == "result_id") ls >> h.result_id;
        } else if (word == "element") {
            std::string name;
            std::uint64_t count = 0;
            ls >> name >> count;
            h.elements.emplace_back(name, ls.fail() ? 0 : count);
            h.layout.push_back("element " + name);
        } else if (word == "property") {
            std::string rest;
            std::getline(ls >> std::ws, rest);
            h.layout.push_back(rest);
        }
    }
    return h;
}

bool FixedPlyHeader::is_vertex_layout(std::span<const std::string> properties) const {
    return binary_little_endian && !layout.empty() && layout[0] == "element vertex" &&
           std::equal(layout.begin() + 1, layout.end(), properties.begin(), properties.end());
}

std::string fixed_ply_head(std::string_view what, std::string_view units,
                           std::string_view result_id, std::size_t count,
                           std::span<const std::string> properties) {
    std::string head =
        cat({"ply\nformat binary_little_endian 1.0\ncomment ", what, "\ncomment units ", units,
             "\ncomment result_id ", result_id, "\nelement vertex ", std::to_string(count), "\n"});
    for (const std::string& p : properties) head += cat({"property ", p, "\n"});
    head += "end_header\n";
    return head;
}

std::size_t record_bytes(std::span<const std::string> properties) {
    std::size_t bytes = 0;
    for (const std::string& p : properties)
        bytes += p.starts_with("double ") ? 8 : p.starts_with("uchar ") ? 1 : 4;
    return bytes;
}

}  // namespace surfgrow::io
