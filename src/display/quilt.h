// The quilt: all views of a frame in one atlas image, laid out as QuiltLayout says (view 0 =
// leftmost camera = bottom-left tile, then left to right, then upwards), and its file name in
// the Looking Glass convention NAME_qs{columns}x{rows}a{aspect}.png, which lets Looking Glass
// tools (and metrics::quilt_layout_from_name) split the atlas back into views.
#pragma once

#include <functional>
#include <span>
#include <string>

#include "display/quilt_layout.h"
#include "display/rgb_image.h"

namespace ddish::display {

// The tiles that atlas row y (row 0 at the top) crosses, in view order: at(view, view_row, x)
// for each of the first `views` views whose tile holds row y, with the view's row and the tile's
// left column. Pixels of the row that no such tile covers are not named (they stay black).
// What compose_quilt and the row-streamed quilt files (app/frame_outputs) are built on.
void for_each_tile_in_row(const QuiltLayout& layout, int views, int y,
                          const std::function<void(int view, int view_row, int x)>& at);

// Copies views[i] into tile i of `out` (which must be layout.width × layout.height) and clears
// every pixel no view covers (unused cells, the spare column/row of a non-divisible atlas).
// Throws std::invalid_argument when out has the wrong size, a view is not tile-sized, or there
// are more views than cells.
void compose_quilt(std::span<const ConstRgbView> views, const QuiltLayout& layout, RgbView out);
RgbImage compose_quilt(std::span<const ConstRgbView> views, const QuiltLayout& layout);

// The aspect as quilt file names write it: truncated (not rounded) to two decimals, then
// trailing zeros and a bare point dropped: 0.75 → "0.75", 16/9 → "1.77", 1.6 → "1.6", 2 → "2".
// Truncation is the Looking Glass habit (a 16:9 display's quilts are "a1.77"); a tolerance of
// 1e-4 keeps a value stored as 0.7499999 reading "0.75". Throws std::invalid_argument unless
// aspect is positive and finite.
std::string format_quilt_aspect(float aspect);

// "NAME_qs{columns}x{rows}a{aspect}{extension}", e.g. "cornell_qs8x6a0.75.png".
std::string quilt_file_name(const std::string& name, const QuiltLayout& layout, float aspect,
                            const std::string& extension = ".png");

}  // namespace ddish::display
