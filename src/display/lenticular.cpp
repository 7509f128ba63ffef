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

// Bilinear sample of one channel of tile `rect` at tile coordinates (u, v), v upwards; texel
// centres at half-integers, clamped to the tile so neighbouring views never bleed in.
float sample_tile(ConstRgbView quilt, const TileRect& rect, double u, double v, int channel) {
  const double tx = std::clamp(u * rect.width - 0.5, 0.0, double(rect.width - 1));
  const double ty = std::clamp((1.0 - v) * rect.height - 0.5, 0.0, double(rect.height - 1));
  const int x0 = static_cast<int>(tx);
  const int y0 = static_cast<int>(ty);
  const int x1 = std::min(x0 + 1, rect.width - 1);
  const int y1 = std::min(y0 + 1, rect.height - 1);
  const float fx = static_cast<float>(tx - x0);
  const float fy = static_cast<float>(ty - y0);
  auto at = [&](int x, int y) { return quilt.pixel(rect.x + x, rect.y + y)[channel]; };
  const float top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * fx;
  const float bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * fx;
  return top + (bottom - top) * fy;
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
  for (int row = 0; row < mapping.screen_height; ++row) {
    const double v = screen_v(mapping, row);
    const double sample_v = mapping.flip_y ? 1.0 - v : v;
    for (int x = 0; x < mapping.screen_width; ++x) {
      const double sample_u = screen_u(mapping, x);
      float* out = panel.pixel(x, row);
      for (int channel = 0; channel < 3; ++channel) {
        const int view = subpixel_view(mapping, x, row, channel, views);
        out[channel] = sample_tile(quilt, layout.tile(view), sample_u, sample_v, channel);
      }
    }
  }
  return panel;
}

}  // namespace ddish::display
