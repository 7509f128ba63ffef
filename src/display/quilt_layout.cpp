#include "display/quilt_layout.h"

#include <stdexcept>
#include <string>

namespace ddish::display {

TileRect QuiltLayout::tile(int view) const {
  if (view < 0 || view >= cells()) {
    throw std::out_of_range("view " + std::to_string(view) + " is outside a " +
                            std::to_string(columns) + "x" + std::to_string(rows) + " quilt");
  }
  const int col = view % columns;
  const int row_from_bottom = view / columns;
  // Tiles hug the bottom-left corner; image rows count from the top, hence the flip.
  return TileRect{col * tile_width, height - (row_from_bottom + 1) * tile_height, tile_width,
                  tile_height};
}

void QuiltLayout::validate() const {
  if (columns <= 0 || rows <= 0) {
    throw std::invalid_argument("quilt layout " + std::to_string(columns) + "x" +
                                std::to_string(rows) + " needs at least one column and row");
  }
  if (tile_width <= 0 || tile_height <= 0) {
    throw std::invalid_argument("quilt tile " + std::to_string(tile_width) + "x" +
                                std::to_string(tile_height) + " must be at least 1x1 pixel");
  }
  if (width < columns * tile_width || height < rows * tile_height) {
    throw std::invalid_argument(
        "quilt " + std::to_string(width) + "x" + std::to_string(height) + " cannot hold " +
        std::to_string(columns) + "x" + std::to_string(rows) + " tiles of " +
        std::to_string(tile_width) + "x" + std::to_string(tile_height));
  }
}

QuiltLayout layout_from_tiles(int columns, int rows, int tile_width, int tile_height) {
  QuiltLayout l{columns, rows, tile_width, tile_height, columns * tile_width, rows * tile_height};
  l.validate();
  return l;
}

QuiltLayout layout_from_atlas(int columns, int rows, int width, int height) {
  if (columns <= 0 || rows <= 0) {
    throw std::invalid_argument("quilt layout " + std::to_string(columns) + "x" +
                                std::to_string(rows) + " needs at least one column and row");
  }
  QuiltLayout l{columns, rows, width / columns, height / rows, width, height};
  l.validate();
  return l;
}

}  // namespace ddish::display
