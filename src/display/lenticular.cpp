#include "display/lenticular.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::display {

namespace {

double screen_u(const LenticularMapping& m, int x) {
  const double u = (double(x) + 0.5) / double(m.screen_width);
  return m.flip_x ? 1.0 - u : u;
}

double screen_v(const LenticularMapping& m, int row) {
  return 1.0 - (double(row) + 0.5) / double(m.screen_height);
}

// Texel centres at half-integers, clamped to the tile so neighbouring views never bleed in.
BilinearTap tap(double t, int size) {
  const double c = std::clamp(t * size - 0.5, 0.0, double(size - 1));
  const int i0 = static_cast<int>(c);
  return BilinearTap{i0, std::min(i0 + 1, size - 1), static_cast<float>(c - i0)};
}

// Bilinear sample of one channel of tile `rect` through the taps of one panel pixel.
float sample_tile(ConstRgbView quilt, const TileRect& rect, const BilinearTap& tx,
                  const BilinearTap& ty, int channel) {
  auto at = [&](int x, int y) { return quilt.pixel(rect.x + x, rect.y + y)[channel]; };
  const float top = at(tx.i0, ty.i0) + (at(tx.i1, ty.i0) - at(tx.i0, ty.i0)) * tx.f;
  const float bottom = at(tx.i0, ty.i1) + (at(tx.i1, ty.i1) - at(tx.i0, ty.i1)) * tx.f;
  return top + (bottom - top) * ty.f;
}

}  // namespace

LenticularMapping lenticular_mapping(const Calibration& c) {
  if (!(c.screen_width > 0 && c.screen_height > 0 && c.dpi > 0.0 && c.slope != 0.0)) {
    throw std::invalid_argument("lenticular calibration needs a positive screen size and DPI and "
                                "a non-zero slope");
  }
  LenticularMapping m;
  m.screen_width = c.screen_width;
  m.screen_height = c.screen_height;
  const double screen_inches = double(c.screen_width) / c.dpi;
  m.pitch = c.pitch * screen_inches * std::cos(std::atan(1.0 / c.slope));
  m.tilt = double(c.screen_height) / (double(c.screen_width) * c.slope) * (c.flip_x ? -1.0 : 1.0);
  m.subp = 1.0 / (3.0 * double(c.screen_width));
  m.center = c.center;
  m.inv_view = c.inv_view;
  m.flip_x = c.flip_x;
  m.flip_y = c.flip_y;
  m.red_sample = c.flip_subpixels ? 2 : 0;
  m.blue_sample = c.flip_subpixels ? 0 : 2;
  return m;
}

double subpixel_phase(const LenticularMapping& m, int x, int row, int sample) {
  const double a =
      (screen_u(m, x) + sample * m.subp + screen_v(m, row) * m.tilt) * m.pitch - m.center;
  double phase = a - std::floor(a);
  if (m.inv_view) phase = 1.0 - phase;
  return phase;
}

int subpixel_view(const LenticularMapping& m, int x, int row, int channel, int views) {
  const int sample = channel == 0 ? m.red_sample : channel == 2 ? m.blue_sample : 1;
  const int view = static_cast<int>(std::floor(subpixel_phase(m, x, row, sample) * views));
  return std::clamp(view, 0, views - 1);
}

BilinearTap tile_tap_x(const LenticularMapping& m, int x, int tile_width) {
  return tap(screen_u(m, x), tile_width);
}

BilinearTap tile_tap_y(const LenticularMapping& m, int row, int tile_height) {
  // v grows upwards, tile rows count from the top.
  const double v = screen_v(m, row);
  return tap(1.0 - (m.flip_y ? 1.0 - v : v), tile_height);
}

RgbImage interleave(ConstRgbView quilt, const QuiltLayout& layout, int views,
                    const LenticularMapping& mapping) {
  layout.validate();
  if (quilt.width != layout.width || quilt.height != layout.height) {
    throw std::invalid_argument("quilt is " + std::to_string(quilt.width) + "x" +
                                std::to_string(quilt.height) + ", its layout says " +
                                std::to_string(layout.width) + "x" +
                                std::to_string(layout.height));
  }
  if (views < 1 || views > layout.cells()) {
    throw std::invalid_argument(std::to_string(views) + " views is not between 1 and the " +
                                std::to_string(layout.cells()) + " quilt cells");
  }
  RgbImage panel(mapping.screen_width, mapping.screen_height);
  const TileRect first = layout.tile(0);
  for (int row = 0; row < mapping.screen_height; ++row) {
    const BilinearTap ty = tile_tap_y(mapping, row, first.height);
    for (int x = 0; x < mapping.screen_width; ++x) {
      const BilinearTap tx = tile_tap_x(mapping, x, first.width);
      float* out = panel.pixel(x, row);
      for (int channel = 0; channel < 3; ++channel) {
        const int view = subpixel_view(mapping, x, row, channel, views);
        out[channel] = sample_tile(quilt, layout.tile(view), tx, ty, channel);
      }
    }
  }
  return panel;
}

}  // namespace ddish::display
