#include "surfgrow/io/scalar_type.hpp"

#include <array>
#include <utility>

namespace surfgrow::io {

std::optional<ScalarType> ply_scalar_type(std::string_view name) {
    static constexpr std::array<std::pair<std::string_view, ScalarType>, 18> kNames{{
        {"char", ScalarType::kInt8},
        {"int8", ScalarType::kInt8},
        {"uchar", ScalarType::kUInt8},
        {"uint8", ScalarType::kUInt8},
        {"short", ScalarType::kInt16},
        {"int16", ScalarType::kInt16},
        {"ushort", ScalarType::kUInt16},
        {"uint16", ScalarType::kUInt16},
        {"int", ScalarType::kInt32},
        {"int32", ScalarType::kInt32},
        {"uint", ScalarType::kUInt32},
        {"uint32", ScalarType::kUInt32},
        {"float", ScalarType::kFloat32},
        {"float32", ScalarType::kFloat32},
        {"double", ScalarType::kFloat64},
        {"float64", ScalarType::kFloat64},
        // Not in the original specification, but written by some tools; harmless to accept.
        {"int64", ScalarType::kInt64},
        {"uint64", ScalarType::kUInt64},
    }};
    for (const auto& [n, t] : kNames) {
        if (n == name) return t;
    }
    return std::nullopt;
}

std::string_view ply_type_name(ScalarType t) {
    switch (t) {
        case ScalarType::kInt8:
            return "char";
        case ScalarType::kUInt8:
            return "uchar";
        case ScalarType::kInt16:
            return "short";
        case ScalarType::kUInt16:
            return "ushort";
        case ScalarType::kInt32:
            return "int";
        case ScalarType::kUInt32:
            return "uint";
        case ScalarType::kInt64:
            return "int64";
        case ScalarType::kUInt64:
            return "uint64";
        case ScalarType::kFloat32:
            return "float";
        case ScalarType::kFloat64:
            break;
    }
    return "double";
}

std::optional<ScalarType> pcd_scalar_type(char type, uint64_t size) {
    switch (type) {
        case 'I':
            if (size == 1) return ScalarType::kInt8;
            if (size == 2) return ScalarType::kInt16;
            if (size == 4) return ScalarType::kInt32;
            if (size == 8) return ScalarType::kInt64;
            break;
        case 'U':
            if (size == 1) return ScalarType::kUInt8;
            if (size == 2) return ScalarType::kUInt16;
            if (size == 4) return ScalarType::kUInt32;
            if (size == 8) return ScalarType::kUInt64;
            break;
        case 'F':
            if (size == 4) return ScalarType::kFloat32;
            if (size == 8) return ScalarType::kFloat64;
            break;
        default:
            break;
    }
    return std::nullopt;
}

}  // namespace surfgrow::io
