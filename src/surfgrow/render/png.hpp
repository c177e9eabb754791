// PNG encoding and decoding of Images (zlib for writing, libpng's simplified API for reading).
#pragma once

#include <istream>
#include <ostream>
#include <string>

#include "surfgrow/render/image.hpp"

namespace surfgrow::render {

/// Encodes `image` as an 8-bit RGB PNG (with sRGB gamma information) onto `out`, which should be
/// binary. Hand it to surfgrow::io::write_atomically to publish a file whole or not at all.
/// Throws Error(kInvalidParameter) for an empty image, Error(kCannotWrite) if `out` fails.
/// `threads` deflate blocks of rows in parallel (0: all cores); the bytes are the same for any.
void write_png(const Image& image, std::ostream& out, int threads = 1);

/// The PNG bytes of `image` (as write_png writes them).
[[nodiscard]] std::string encode_png(const Image& image, int threads = 1);

/// Decodes any PNG libpng reads (grey, palette, 16-bit, alpha composited on black) to 8-bit RGB.
/// Throws Error(kMalformedInput) if the bytes are not a valid PNG.
[[nodiscard]] Image decode_png(const std::string& bytes);
[[nodiscard]] Image read_png(std::istream& in);

}  // namespace surfgrow::render
