// Test helpers for the live window's status text (display/status_font.h): the box drawn on the
// CPU from the font table and the header's layout rules (written here again, independently of
// shaders/status_text.comp), and a reader that turns a box of pixels back into its lines by
// matching every cell against every glyph.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "display/status_font.h"

namespace ddish::display::test {

// The box's pixel (x, y) < (status_box_width, status_box_height) as packed RGBA8.
inline std::uint32_t status_pixel(std::span<const std::string> lines, int scale, int x, int y) {
  const int u = x / scale - kTextPadding, v = y / scale - kTextPadding;
  if (u < 0 || v < 0) return kTextPaper;
  const int column = u / kCellWidth, cx = u % kCellWidth, line = v / kCellHeight, cy = v % kCellHeight;
  if (column >= kStatusColumns || line >= int(lines.size()) || cx >= kGlyphWidth || cy >= kGlyphHeight)
    return kTextPaper;
  const std::string& text = lines[std::size_t(line)];
  const char c = std::size_t(column) < text.size() ? text[std::size_t(column)] : ' ';
  const Glyph& g = font_glyphs()[glyph_index(c)];
  return (g[std::size_t(cy)] >> (kGlyphWidth - 1 - cx)) & 1u ? kTextInk : kTextPaper;
}

// Draws the box into an image of w × h packed RGBA8 pixels (row 0 at the top), clipped.
inline void draw_status(std::vector<std::uint32_t>& image, std::size_t offset, int w, int h,
                        std::span<const std::string> lines, int scale) {
  for (int y = 0; y < std::min(h, status_box_height(int(lines.size()), scale)); ++y)
    for (int x = 0; x < std::min(w, status_box_width(scale)); ++x)
      image[offset + std::size_t(y) * std::size_t(w) + std::size_t(x)] = status_pixel(lines, scale, x, y);
}

// Reads `lines` lines back from `rgb(x, y)` (0xRRGGBB-ordered as R | G << 8 | B << 16) at
// `scale`: each cell's pixels must all be ink or paper, its gaps paper, and its glyph one of the
// font's; otherwise the character is '~' (not in the font). Trailing spaces are dropped.
inline std::vector<std::string> read_status(const std::function<std::uint32_t(int, int)>& rgb,
                                            int lines, int scale) {
  const std::uint32_t ink = kTextInk & 0xFFFFFFu, paper = kTextPaper & 0xFFFFFFu;
  std::vector<std::string> out;
  for (int l = 0; l < lines; ++l) {
    std::string text;
    for (int c = 0; c < kStatusColumns; ++c) {
      Glyph seen{};
      bool clean = true;
      for (int cy = 0; cy < kCellHeight; ++cy)
        for (int cx = 0; cx < kCellWidth; ++cx)
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) {
              const int x = (kTextPadding + c * kCellWidth + cx) * scale + sx;
              const int y = (kTextPadding + l * kCellHeight + cy) * scale + sy;
              if (c == kStatusColumns - 1 && cx >= kGlyphWidth) continue;  // the padding's
              if (l == lines - 1 && cy >= kGlyphHeight) continue;
              const std::uint32_t p = rgb(x, y) & 0xFFFFFFu;
              if (p != (rgb(x - sx, y - sy) & 0xFFFFFFu)) clean = false;  // one colour per block
              const bool gap = cx >= kGlyphWidth || cy >= kGlyphHeight;
              if (p != ink && p != paper) clean = false;
              if (gap && p != paper) clean = false;
              if (!gap && p == ink) seen[std::size_t(cy)] = std::uint8_t(seen[std::size_t(cy)] | (1u << (kGlyphWidth - 1 - cx)));
            }
      char got = '~';
      const auto glyphs = font_glyphs();
      for (std::size_t g = 0; clean && g < glyphs.size(); ++g)
        if (glyphs[g] == seen) got = font_characters()[g];
      text += got;
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out.push_back(text);
  }
  return out;
}

}  // namespace ddish::display::test
