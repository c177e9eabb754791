// The binary scalar types of PLY properties and PCD fields, and loading them from raw bytes.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <type_traits>

namespace surfgrow::io {

enum class ScalarType : uint8_t {
    kInt8,
    kUInt8,
    kInt16,
    kUInt16,
    kInt32,
    kUInt32,
    kInt64,
    kUInt64,
    kFloat32,
    kFloat64,
};

[[nodiscard]] constexpr std::size_t scalar_size(ScalarType t) {
    switch (t) {
        case ScalarType::kInt8:
        case ScalarType::kUInt8:
            return 1;
        case ScalarType::kInt16:
        case ScalarType::kUInt16:
            return 2;
        case ScalarType::kInt32:
        case ScalarType::kUInt32:
        case ScalarType::kFloat32:
            return 4;
        case ScalarType::kInt64:
        case ScalarType::kUInt64:
        case ScalarType::kFloat64:
            return 8;
    }
    return 0;
}

[[nodiscard]] constexpr bool is_integer(ScalarType t) {
    return t != ScalarType::kFloat32 && t != ScalarType::kFloat64;
}

/// True for types whose values a float cannot hold exactly; coordinates of such types are read
/// relative to an offset when they are large (see PointBuilder).
[[nodiscard]] constexpr bool is_wide(ScalarType t) {
    return t == ScalarType::kFloat64 || (scalar_size(t) >= 4 && t != ScalarType::kFloat32);
}

/// PLY type names: char uchar short ushort int uint float double and the sized aliases.
[[nodiscard]] std::optional<ScalarType> ply_scalar_type(std::string_view name);
[[nodiscard]] std::string_view ply_type_name(ScalarType t);

/// PCD TYPE letter (I, U, F) and SIZE in bytes; nullopt for combinations PCD does not define.
[[nodiscard]] std::optional<ScalarType> pcd_scalar_type(char type, uint64_t size);

/// The C++ type of each ScalarType, for templates.
template <ScalarType>
struct ScalarOf;
template <>
struct ScalarOf<ScalarType::kInt8> {
    using type = int8_t;
};
template <>
struct ScalarOf<ScalarType::kUInt8> {
    using type = uint8_t;
};
template <>
struct ScalarOf<ScalarType::kInt16> {
    using type = int16_t;
};
template <>
struct ScalarOf<ScalarType::kUInt16> {
    using type = uint16_t;
};
template <>
struct ScalarOf<ScalarType::kInt32> {
    using type = int32_t;
};
template <>
struct ScalarOf<ScalarType::kUInt32> {
    using type = uint32_t;
};
template <>
struct ScalarOf<ScalarType::kInt64> {
    using type = int64_t;
};
template <>
struct ScalarOf<ScalarType::kUInt64> {
    using type = uint64_t;
};
template <>
struct ScalarOf<ScalarType::kFloat32> {
    using type = float;
};
template <>
struct ScalarOf<ScalarType::kFloat64> {
    using type = double;
};

/// Calls f(T{}) with T the C++ type of `t`, so one template serves every type.
template <typename F>
decltype(auto) visit_scalar(ScalarType t, F&& f) {
    switch (t) {
        case ScalarType::kInt8:
            return f(int8_t{});
        case ScalarType::kUInt8:
            return f(uint8_t{});
        case ScalarType::kInt16:
            return f(int16_t{});
        case ScalarType::kUInt16:
            return f(uint16_t{});
        case ScalarType::kInt32:
            return f(int32_t{});
        case ScalarType::kUInt32:
            return f(uint32_t{});
        case ScalarType::kInt64:
            return f(int64_t{});
        case ScalarType::kUInt64:
            return f(uint64_t{});
        case ScalarType::kFloat32:
            return f(float{});
        case ScalarType::kFloat64:
            break;
    }
    return f(double{});
}

template <std::size_t N>
struct UIntOfSize;
template <>
struct UIntOfSize<1> {
    using type = uint8_t;
};
template <>
struct UIntOfSize<2> {
    using type = uint16_t;
};
template <>
struct UIntOfSize<4> {
    using type = uint32_t;
};
template <>
struct UIntOfSize<8> {
    using type = uint64_t;
};

/// Reverses the bytes of an arithmetic value (big-endian files on a little-endian host).
template <typename T>
[[nodiscard]] inline T byteswap_value(T v) {
    using U = typename UIntOfSize<sizeof(T)>::type;
    U u = std::bit_cast<U>(v);
    if constexpr (sizeof(T) == 2) {
        u = __builtin_bswap16(u);
    } else if constexpr (sizeof(T) == 4) {
        u = __builtin_bswap32(u);
    } else if constexpr (sizeof(T) == 8) {
        u = __builtin_bswap64(u);
    }
    return std::bit_cast<T>(u);
}

/// Loads a T from unaligned bytes, swapping them when the file's byte order is not the host's.
template <typename T, bool kSwap>
[[nodiscard]] inline T load_value(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    if constexpr (kSwap && sizeof(T) > 1) v = byteswap_value(v);
    return v;
}

/// Loads a value of run-time type `t` as double (for the rare slow paths).
[[nodiscard]] inline double load_as_double(const char* p, ScalarType t, bool swap) {
    return visit_scalar(t, [&](auto tag) {
        using T = decltype(tag);
        return static_cast<double>(swap ? load_value<T, true>(p) : load_value<T, false>(p));
    });
}

/// True when the files' little-endian data needs no swapping on this machine.
inline constexpr bool kHostIsLittleEndian = std::endian::native == std::endian::little;

}  // namespace surfgrow::io
