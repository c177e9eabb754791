#include "picture_options.hpp"

#include <charconv>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::cli {

std::pair<int, int> parse_image_size(std::string_view text, std::string_view option) {
    const auto x = text.find_first_of("xX");
    int size[2] = {0, 0};
    bool ok = x != std::string_view::npos;
    for (int k = 0; ok && k < 2; ++k) {
        const std::string_view part = k == 0 ? text.substr(0, x) : text.substr(x + 1);
        const auto r = std::from_chars(part.data(), part.data() + part.size(), size[k]);
        ok = !part.empty() && r.ec == std::errc() && r.ptr == part.data() + part.size();
    }
    if (!ok)
        throw Error(ErrorCode::kUsage,
                    cat({option, ": '", text, "' is not a size in pixels (e.g. 1600x1200)"}));
    constexpr int kMin = 16, kMax = 16384;
    if (size[0] < kMin || size[0] > kMax || size[1] < kMin || size[1] > kMax)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({option, ": ", text, " is out of range (16 to 16384 pixels a side)"}));
    return {size[0], size[1]};
}

}  // namespace surfgrow::cli
