#include "surfgrow/render/image.hpp"

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::render {

Image::Image(int width, int height, Rgb fill) : width_(width), height_(height) {
    if (width < 0 || height < 0)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"image size must not be negative, got ", num(width), " x ", num(height)}));
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    bytes_.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        bytes_[3 * i] = fill.r;
        bytes_[3 * i + 1] = fill.g;
        bytes_[3 * i + 2] = fill.b;
    }
}

std::size_t Image::count(Rgb c) const {
    std::size_t n = 0;
    for (std::size_t i = 0; i + 2 < bytes_.size(); i += 3)
        n += bytes_[i] == c.r && bytes_[i + 1] == c.g && bytes_[i + 2] == c.b;
    return n;
}

}  // namespace surfgrow::render
