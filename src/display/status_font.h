// The live window's status text (display/gpu_compositor.h draws it): our own 5 × 7 bitmap font
// of capitals, digits and a little punctuation, and how a block of lines is laid out in a dark
// box. The layout in unscaled pixels, every length then multiplied by the integer `scale`:
//   the box is kStatusColumns cells wide and `lines` cells high, plus kTextPadding on each side;
//   cell (column c, line l) starts at (kTextPadding + 6c, kTextPadding + 9l): a glyph of 5 × 7
//   and a gap of 1 to the right and 2 below (the last column's and line's gaps are the padding's);
//   a glyph pixel that is set is kTextInk, every other pixel of the box kTextPaper.
// Both are opaque, so drawing the same text twice gives the same pixels. The box's top-left
// corner is the image's (0, 0); what falls outside the image is left out.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ddish::display {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kCellWidth = 6;
inline constexpr int kCellHeight = 9;
inline constexpr int kTextPadding = 2;
inline constexpr int kStatusColumns = 56;  // longer lines are cut
inline constexpr std::uint32_t kTextInk = 0xFFFFFFFFu;    // packed RGBA8: white
inline constexpr std::uint32_t kTextPaper = 0xFF202020u;  // dark grey

// One glyph: row 0 at the top; bit (4 − x) of a row is the pixel x from the left.
using Glyph = std::array<std::uint8_t, kGlyphHeight>;

// The font's characters in glyph order (index 0 is the space).
std::string_view font_characters();
std::span<const Glyph> font_glyphs();

// The glyph index of `c`: small letters as capitals, anything the font lacks as '?'.
std::uint32_t glyph_index(char c);

// The box of `lines` lines at `scale`, in pixels.
int status_box_width(int scale);
int status_box_height(int lines, int scale);

// The cells of `lines` as glyph indices, kStatusColumns per line (line after line), padded with
// spaces and cut at kStatusColumns.
std::vector<std::uint32_t> status_cells(std::span<const std::string> lines);

}  // namespace ddish::display
