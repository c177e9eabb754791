// Base64 (RFC 4648, with padding): how binary arrays travel inside the HTML page.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace surfgrow::view {

/// Appends the base64 encoding of `size` bytes at `data` to `out`.
void append_base64(std::string& out, const void* data, std::size_t size);

/// Decodes padded base64 (no whitespace); nullopt if `text` is not valid base64.
[[nodiscard]] std::optional<std::string> decode_base64(std::string_view text);

}  // namespace surfgrow::view
