#include "surfgrow/render/font.hpp"

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <system_error>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::render {

namespace fs = std::filesystem;

struct Font::Impl {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    int pixel_size = 0;

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() {
        if (face) FT_Done_Face(face);
        if (library) FT_Done_FreeType(library);
    }

    // Lays out `utf8` glyph by glyph: calls `glyph(pen_x)` with the glyph slot loaded (and
    // rendered if `render`), pen_x in 26.6 fixed point. Returns the final pen position.
    template <typename F>
    long layout(std::string_view utf8, bool render, F&& glyph) const;
};

namespace {

// Decodes one UTF-8 code point at s[i], advancing i; malformed bytes give U+FFFD.
char32_t next_code_point(std::string_view s, std::size_t& i) {
    const auto b0 = static_cast<unsigned char>(s[i++]);
    if (b0 < 0x80) return b0;
    int extra = b0 >= 0xF0 && b0 < 0xF8 ? 3 : b0 >= 0xE0 ? 2 : b0 >= 0xC0 ? 1 : -1;
    if (extra < 0) return 0xFFFD;
    char32_t cp = b0 & (0x3F >> extra);
    for (; extra > 0; --extra) {
        if (i >= s.size()) return 0xFFFD;
        const auto b = static_cast<unsigned char>(s[i]);
        if ((b & 0xC0) != 0x80) return 0xFFFD;
        cp = (cp << 6) | (b & 0x3F);
        ++i;
    }
    return cp;
}

std::optional<fs::path> fontconfig_match(const char* name) {
    FcConfig* config = FcInitLoadConfigAndFonts();
    if (!config) return std::nullopt;
    std::optional<fs::path> found;
    if (FcPattern* pattern = FcNameParse(reinterpret_cast<const FcChar8*>(name))) {
        FcConfigSubstitute(config, pattern, FcMatchPattern);
        FcDefaultSubstitute(pattern);
        FcResult result = FcResultNoMatch;
        if (FcPattern* match = FcFontMatch(config, pattern, &result)) {
            FcChar8* file = nullptr;
            if (FcPatternGetString(match, FC_FILE, 0, &file) == FcResultMatch && file)
                found = fs::path(reinterpret_cast<const char*>(file));
            FcPatternDestroy(match);
        }
        FcPatternDestroy(pattern);
    }
    FcConfigDestroy(config);
    return found;
}

}  // namespace

template <typename F>
long Font::Impl::layout(std::string_view utf8, bool render, F&& glyph) const {
    long pen = 0;
    FT_UInt previous = 0;
    const bool kerning = FT_HAS_KERNING(face);
    for (std::size_t i = 0; i < utf8.size();) {
        const FT_UInt index = FT_Get_Char_Index(face, next_code_point(utf8, i));
        if (kerning && previous && index) {
            FT_Vector delta{0, 0};
            if (!FT_Get_Kerning(face, previous, index, FT_KERNING_DEFAULT, &delta)) pen += delta.x;
        }
        if (FT_Load_Glyph(face, index, render ? FT_LOAD_RENDER : FT_LOAD_DEFAULT) == 0) {
            glyph(pen);
            pen += face->glyph->advance.x;
        }
        previous = index;
    }
    return pen;
}

Font::Font(const fs::path& file, int pixel_size) : impl_(std::make_unique<Impl>()) {
    if (pixel_size < 4 || pixel_size > 512)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"font size must be 4 to 512 pixels, got ", num(pixel_size)}));
    if (FT_Init_FreeType(&impl_->library))
        throw Error(ErrorCode::kInternal, "cannot initialise FreeType");
    if (FT_New_Face(impl_->library, file.c_str(), 0, &impl_->face)) {
        impl_->face = nullptr;
        throw Error(ErrorCode::kCannotOpen, cat({"cannot load the font ", file.string()}));
    }
    if (FT_Set_Pixel_Sizes(impl_->face, 0, static_cast<FT_UInt>(pixel_size)))
        throw Error(ErrorCode::kCannotOpen,
                    cat({"the font ", file.string(), " has no size ", num(pixel_size)}));
    impl_->pixel_size = pixel_size;
}

Font::~Font() = default;
Font::Font(Font&&) noexcept = default;
Font& Font::operator=(Font&&) noexcept = default;

std::optional<fs::path> Font::find_default() {
    static const std::optional<fs::path> found = []() -> std::optional<fs::path> {
        const fs::path debian = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
        std::error_code ec;
        if (fs::is_regular_file(debian, ec)) return debian;
        for (const char* name : {"DejaVu Sans", "sans-serif"})
            if (auto file = fontconfig_match(name); file && fs::is_regular_file(*file, ec))
                return file;
        return std::nullopt;
    }();
    return found;
}

int Font::pixel_size() const {
    return impl_->pixel_size;
}
int Font::ascent() const {
    return static_cast<int>(impl_->face->size->metrics.ascender >> 6);
}
int Font::descent() const {
    return static_cast<int>(-(impl_->face->size->metrics.descender >> 6));
}

int Font::measure(std::string_view utf8) const {
    const long pen = impl_->layout(utf8, false, [](long) {});
    return static_cast<int>((pen + 32) >> 6);
}

int Font::draw(Image& image, int x, int baseline, std::string_view utf8, Rgb color) const {
    const FT_GlyphSlot slot = impl_->face->glyph;
    const long pen = impl_->layout(utf8, true, [&](long pen_x) {
        const FT_Bitmap& bm = slot->bitmap;
        if (bm.pixel_mode != FT_PIXEL_MODE_GRAY || bm.num_grays < 2) return;
        const int left = x + static_cast<int>((pen_x + 32) >> 6) + slot->bitmap_left;
        const int top = baseline - slot->bitmap_top;
        const double full = bm.num_grays - 1;
        for (unsigned r = 0; r < bm.rows; ++r) {
            const unsigned char* row = bm.buffer + static_cast<long>(r) * bm.pitch;
            for (unsigned c = 0; c < bm.width; ++c) {
                const int px = left + static_cast<int>(c), py = top + static_cast<int>(r);
                if (row[c] && image.contains(px, py)) image.blend(px, py, color, row[c] / full);
            }
        }
    });
    return x + static_cast<int>((pen + 32) >> 6);
}

}  // namespace surfgrow::render
