// Text for legends and labels: a TrueType font rasterized by FreeType, blended onto an Image.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>

#include "surfgrow/render/image.hpp"

namespace surfgrow::render {

/// One font face at one pixel size. Not thread-safe: use one Font per thread.
class Font {
  public:
    /// Loads `file` (TrueType/OpenType) at `pixel_size` (em height in pixels, 4..512).
    /// Throws Error(kCannotOpen) if the file cannot be loaded as a font, Error(kInvalidParameter)
    /// for a size out of range.
    Font(const std::filesystem::path& file, int pixel_size);
    ~Font();
    Font(Font&&) noexcept;
    Font& operator=(Font&&) noexcept;
    Font(const Font&) = delete;
    Font& operator=(const Font&) = delete;

    /// DejaVu Sans from Debian's fonts-dejavu-core, else whatever fontconfig offers for
    /// "DejaVu Sans" / "sans-serif"; nullopt if there is no font on the machine.
    [[nodiscard]] static std::optional<std::filesystem::path> find_default();

    [[nodiscard]] int pixel_size() const;
    /// Pixels from the baseline up to the top of the tallest glyphs (positive).
    [[nodiscard]] int ascent() const;
    /// Pixels from the baseline down to the bottom of descenders (positive).
    [[nodiscard]] int descent() const;

    /// Width in pixels of a UTF-8 string as draw() sets it.
    [[nodiscard]] int measure(std::string_view utf8) const;
    /// Draws a UTF-8 string (antialiased) with its baseline at row `baseline`, starting at column
    /// `x`; clipped to the image. Returns the column after the last glyph.
    int draw(Image& image, int x, int baseline, std::string_view utf8, Rgb color) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace surfgrow::render
