// Scanning text bodies: lines, blank-separated tokens and numbers, without allocating per value.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "surfgrow/core/text.hpp"  // is_blank, trim

namespace surfgrow::io {

/// Parses a whole token as a double (std::from_chars, so independent of the locale). Accepts a
/// leading '+' and nan/inf in any case; values beyond double's range become +-inf or 0, as with
/// strtod. False when any character is left over.
[[nodiscard]] bool parse_double(std::string_view token, double& out);

/// The same, rounding the decimal straight to float: every float's shortest text (to_chars)
/// reads back as that float, which a double rounded to float does not guarantee (7.038531e-26).
[[nodiscard]] bool parse_float(std::string_view token, float& out);

/// Parses a whole token as an unsigned decimal integer (no sign); false on overflow.
[[nodiscard]] bool parse_uint(std::string_view token, uint64_t& out);

/// Splits `line` on runs of blanks into at most `max_tokens` tokens (the rest is ignored, so a
/// hostile line cannot make `out` huge). `out` is reused: a parser allocates once, not per line.
void split_blanks(std::string_view line, std::vector<std::string_view>& out,
                  std::size_t max_tokens = SIZE_MAX);

/// The lines of a text without their '\n' and trailing '\r', numbered for messages.
class LineReader {
  public:
    explicit LineReader(std::string_view text, std::size_t first_line = 1)
        : text_(text), next_line_(first_line) {}

    /// Sets `line` to the next line; false at the end of the text.
    bool next(std::string_view& line);
    /// Number of the line last returned.
    [[nodiscard]] std::size_t line_number() const { return next_line_ - 1; }
    /// Offset in the text just past the line last returned, its '\n' included.
    [[nodiscard]] std::size_t offset() const { return pos_; }

  private:
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t next_line_;
};

/// The blank-separated tokens of a body in which line breaks are just blanks (ASCII PLY), with
/// the line number of the last token for messages.
class TokenReader {
  public:
    TokenReader(std::string_view text, std::size_t first_line) : text_(text), line_(first_line) {}

    /// Sets `token` to the next token; false when only blanks remain.
    bool next(std::string_view& token);
    /// Line of the token last returned (or of the end of the text).
    [[nodiscard]] std::size_t line_number() const { return line_; }
    /// True when only blanks remain.
    [[nodiscard]] bool at_end();

  private:
    void skip_blanks();
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_;
};

}  // namespace surfgrow::io
