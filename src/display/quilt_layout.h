// Where each view sits in a multi-view atlas (a Looking Glass "quilt", a light-field atlas, a
// side-by-side stereo pair). The convention is the Looking Glass one (DESIGN.md "Display
// profiles"): view 0 = the leftmost camera = the bottom-left tile, then left to right, then
// upwards. The atlas may be a little larger than columns × tile (4096 / 5 = 819.2): the tiles
// then keep to the bottom-left corner, as a Looking Glass reads them (its "view portion" scales
// texture coordinates from the bottom-left), and the spare column/row on the right/top stays black.
#pragma once

namespace ddish::display {

struct TileRect {
  int x = 0;  // left column of the tile in the atlas image (row 0 = top)
  int y = 0;  // top row of the tile in the atlas image
  int width = 0;
  int height = 0;
};

struct QuiltLayout {
  int columns = 1;
  int rows = 1;
  int tile_width = 0;
  int tile_height = 0;
  int width = 0;   // atlas size in pixels, at least columns × tile_width
  int height = 0;  // at least rows × tile_height

  int cells() const { return columns * rows; }
  // The pixel rectangle of view `view` (0 ≤ view < cells()); throws std::out_of_range otherwise.
  TileRect tile(int view) const;
  // Throws std::invalid_argument (one line) unless every size is positive and the tiles fit.
  void validate() const;
};

// An atlas exactly columns × tile wide and rows × tile high.
QuiltLayout layout_from_tiles(int columns, int rows, int tile_width, int tile_height);

// An atlas of a given size whose tiles are the whole pixels that fit: tile = floor(size / count)
// (a 4096² quilt of 5 × 9 has 819 × 455 tiles and one spare pixel column and row).
QuiltLayout layout_from_atlas(int columns, int rows, int width, int height);

}  // namespace ddish::display
