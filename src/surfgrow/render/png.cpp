#include "surfgrow/render/png.hpp"

#include <png.h>

#include <cstdint>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::render {

namespace {

// Frees libpng's read state on every path out of decode_png (the simplified API allocates it).
struct ImageGuard {
    png_image* image;
    ~ImageGuard() { png_image_free(image); }
};

}  // namespace

std::string encode_png(const Image& image) {
    if (image.empty())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"cannot encode an empty image as PNG (", num(image.width()), " x ",
                         num(image.height()), ")"}));
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    info.width = static_cast<png_uint_32>(image.width());
    info.height = static_cast<png_uint_32>(image.height());
    info.format = PNG_FORMAT_RGB;
    // The bound is exact enough to write in one pass: no trial compression to learn the size.
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(info);
    std::string out(size, '\0');
    const auto stride = static_cast<png_int_32>(image.row_stride());
    if (!png_image_write_to_memory(&info, out.data(), &size, 0, image.bytes().data(), stride,
                                   nullptr))
        throw Error(ErrorCode::kInternal, cat({"PNG encoding failed: ", info.message}));
    out.resize(size);
    return out;
}

void write_png(const Image& image, std::ostream& out) {
    const std::string bytes = encode_png(image);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw Error(ErrorCode::kCannotWrite, "cannot write the PNG image to its stream");
}

Image decode_png(const std::string& bytes) {
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    ImageGuard guard{&info};
    if (!png_image_begin_read_from_memory(&info, bytes.data(), bytes.size()))
        throw Error(ErrorCode::kMalformedInput, cat({"not a readable PNG: ", info.message}));
    // A header may claim any size; refuse what no picture of ours comes near (256 Mpixel).
    if (std::uint64_t(info.width) * info.height > (std::uint64_t(1) << 28))
        throw Error(ErrorCode::kMalformedInput,
                    cat({"PNG too large: ", num(info.width), " x ", num(info.height)}));
    info.format = PNG_FORMAT_RGB;
    Image image(static_cast<int>(info.width), static_cast<int>(info.height));
    const png_color black{0, 0, 0};
    if (!png_image_finish_read(&info, &black, image.bytes().data(),
                               static_cast<png_int_32>(image.row_stride()), nullptr))
        throw Error(ErrorCode::kMalformedInput, cat({"corrupt PNG: ", info.message}));
    return image;
}

Image read_png(std::istream& in) {
    std::string bytes;
    char chunk[65536];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0)
        bytes.append(chunk, static_cast<std::size_t>(in.gcount()));
    return decode_png(bytes);
}

}  // namespace surfgrow::render
