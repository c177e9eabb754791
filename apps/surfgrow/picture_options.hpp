// Options shared by the picture commands (render, view).
#pragma once

#include <string_view>
#include <utility>

namespace surfgrow::cli {

/// Parses "1600x1200" (width x height in pixels, 16 to 16384 each). Throws Error(kUsage) for
/// bad syntax and Error(kInvalidParameter) for a size out of range, naming `option`.
[[nodiscard]] std::pair<int, int> parse_image_size(std::string_view text, std::string_view option);

}  // namespace surfgrow::cli
