#include "display/quilt.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ddish::display {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

void compose_quilt(std::span<const ConstRgbView> views, const QuiltLayout& layout, RgbView out) {
  layout.validate();
  if (out.width != layout.width || out.height != layout.height) {
    throw std::invalid_argument("quilt image is " + size_text(out.width, out.height) +
                                ", the layout needs " + size_text(layout.width, layout.height));
  }
  if (static_cast<int>(views.size()) > layout.cells()) {
    throw std::invalid_argument(std::to_string(views.size()) + " views do not fit a " +
                                size_text(layout.columns, layout.rows) + " quilt");
  }
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (views[i].width != layout.tile_width || views[i].height != layout.tile_height) {
      throw std::invalid_argument("view " + std::to_string(i) + " is " +
                                  size_text(views[i].width, views[i].height) +
                                  ", quilt tiles are " +
                                  size_text(layout.tile_width, layout.tile_height));
    }
  }
  std::fill(out.data, out.data + 3 * std::size_t(out.width) * std::size_t(out.height), 0.0f);
  const std::size_t row_floats = 3 * static_cast<std::size_t>(layout.tile_width);
  for (int y = 0; y < layout.height; ++y)
    for_each_tile_in_row(layout, static_cast<int>(views.size()), y, [&](int view, int view_row, int x) {
      std::copy_n(views[std::size_t(view)].pixel(0, view_row), row_floats, out.pixel(x, y));
    });
}

void for_each_tile_in_row(const QuiltLayout& layout, int views, int y,
                          const std::function<void(int view, int view_row, int x)>& at) {
  // Views and the atlas both store row 0 at the top, so a tile's rows follow unflipped.
  for (int i = 0; i < views; ++i) {
    const TileRect r = layout.tile(i);
    if (y >= r.y && y < r.y + r.height) at(i, y - r.y, r.x);
  }
}

RgbImage compose_quilt(std::span<const ConstRgbView> views, const QuiltLayout& layout) {
  layout.validate();
  RgbImage quilt(layout.width, layout.height);
  compose_quilt(views, layout, quilt.view());
  return quilt;
}

std::string format_quilt_aspect(float aspect) {
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) {
    throw std::invalid_argument("quilt aspect " + std::to_string(aspect) + " must be positive");
  }
  const auto hundredths = static_cast<long long>(std::floor(double(aspect) * 100.0 + 1e-4));
  std::string text = std::to_string(hundredths / 100);
  const int frac = static_cast<int>(hundredths % 100);
  if (frac != 0) {
    text += '.';
    text += static_cast<char>('0' + frac / 10);
    if (frac % 10 != 0) text += static_cast<char>('0' + frac % 10);
  }
  return text;
}

std::string quilt_file_name(const std::string& name, const QuiltLayout& layout, float aspect,
                            const std::string& extension) {
  return name + "_qs" + std::to_string(layout.columns) + "x" + std::to_string(layout.rows) + "a" +
         format_quilt_aspect(aspect) + extension;
}

}  // namespace ddish::display
