#include "surfgrow/io/cloud_options.hpp"

namespace surfgrow::io {

std::string_view to_string(CloudFormat format) {
    switch (format) {
        case CloudFormat::kPly:
            return "PLY";
        case CloudFormat::kPcd:
            return "PCD";
        case CloudFormat::kText:
            break;
    }
    return "text";
}

std::string_view to_string(PlyEncoding encoding) {
    switch (encoding) {
        case PlyEncoding::kAscii:
            return "ascii";
        case PlyEncoding::kBinaryLittleEndian:
            return "binary_little_endian";
        case PlyEncoding::kBinaryBigEndian:
            break;
    }
    return "binary_big_endian";
}

std::string_view to_string(PcdEncoding encoding) {
    switch (encoding) {
        case PcdEncoding::kAscii:
            return "ascii";
        case PcdEncoding::kBinary:
            return "binary";
        case PcdEncoding::kBinaryCompressed:
            break;
    }
    return "binary_compressed";
}

}  // namespace surfgrow::io
