#include "app/frame_outputs.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "display/lenticular.h"
#include "display/quilt.h"
#include "metrics/color.h"
#include "metrics/image_io.h"
#include "raster/renderer.h"

namespace ddish::app {

namespace fs = std::filesystem;

namespace {

std::string tagged(const std::string& name, const std::string& tag) {
  return tag.empty() ? name : name + "_" + tag;
}

template <typename Views>
void check_sizes(const Views& views, const char* what) {
  if (views.empty()) throw std::invalid_argument(std::string("a frame needs at least one ") + what);
  for (const auto& v : views)
    if (v.width() != views.front().width() || v.height() != views.front().height() || v.width() <= 0)
      throw std::invalid_argument(std::string("every ") + what + " of a frame needs the same positive size");
}

struct ViewImageSize {  // raster::ViewImage has fields, not accessors
  const raster::ViewImage& v;
  int width() const { return v.width; }
  int height() const { return v.height; }
};

}  // namespace

RasterFrameViews::RasterFrameViews(std::span<const raster::ViewImage> views) : views_(views) {
  std::vector<ViewImageSize> sizes;
  for (const raster::ViewImage& v : views) sizes.push_back({v});
  check_sizes(sizes, "view");
}

void RasterFrameViews::linear_row(std::size_t view, int y, float* rgb) const {
  const raster::ViewImage& v = views_[view];
  const std::size_t w = std::size_t(v.width);
  v.linear.read(std::size_t(y) * w, w, rgb);
}

void RasterFrameViews::display_row(std::size_t view, int y, std::uint8_t* rgb) const {
  const raster::ViewImage& v = views_[view];
  const std::size_t w = std::size_t(v.width);
  const std::uint32_t* p = &v.display[std::size_t(y) * w];
  for (std::size_t x = 0; x < w; ++x) {  // packed RGBA8, R in the low byte; alpha is dropped
    rgb[3 * x] = std::uint8_t(p[x] & 0xffu);
    rgb[3 * x + 1] = std::uint8_t((p[x] >> 8) & 0xffu);
    rgb[3 * x + 2] = std::uint8_t((p[x] >> 16) & 0xffu);
  }
}

LinearFrameViews::LinearFrameViews(std::span<const metrics::Image> images, float display_scale)
    : images_(images), display_scale_(display_scale) {
  check_sizes(images, "image");
}

void LinearFrameViews::linear_row(std::size_t view, int y, float* rgb) const {
  const metrics::Image& img = images_[view];
  const std::size_t w = std::size_t(img.width());
  std::memcpy(rgb, &img.pixels()[std::size_t(y) * w].x, 3 * w * sizeof(float));
}

void LinearFrameViews::display_row(std::size_t view, int y, std::uint8_t* rgb) const {
  const metrics::Image& img = images_[view];
  const std::size_t w = std::size_t(img.width());
  const glm::vec3* p = &img.pixels()[std::size_t(y) * w];
  for (std::size_t x = 0; x < w; ++x)
    for (int c = 0; c < 3; ++c)
      rgb[3 * x + std::size_t(c)] = metrics::srgb8_encode(p[x][c] * display_scale_);
}

FrameWriter::FrameWriter(const display::ViewSet& set, OutputOptions options)
    : kind_(set.kind),
      layout_(set.layout),
      aspect_(set.aspect),
      views_(set.size()),
      options_(std::move(options)) {
  const bool quilt = kind_ == display::ViewSetKind::LightField || kind_ == display::ViewSetKind::Grid;
  if (options_.calibration && !quilt)
    throw std::invalid_argument(fmt::format(
        "--calibration interleaves a quilt; the {} display makes none", display::to_string(kind_)));
  if (!options_.png && !options_.exr) throw std::invalid_argument("no output format: PNG, EXR or both");
}

std::string FrameWriter::atlas_name(const std::string& tag, const std::string& extension) const {
  const std::string name = tagged(options_.stem, tag);
  if (kind_ == display::ViewSetKind::Stereo)
    return display::quilt_file_name(name + "_sbs", layout_, aspect_, extension);
  return display::quilt_file_name(name, layout_, aspect_, extension);
}

std::vector<fs::path> FrameWriter::write(const FrameViews& views, const std::string& single,
                                         const std::string& tag) const {
  if (views.count() != views_ || views.width() != layout_.tile_width || views.height() != layout_.tile_height)
    throw std::invalid_argument(fmt::format("a frame of {} views of {}x{} got {} of {}x{}", views_,
                                            layout_.tile_width, layout_.tile_height, views.count(),
                                            views.width(), views.height()));
  std::vector<fs::path> written;
  // One view's files, or the atlas of all views: rows gathered from the views' rows.
  auto write_pair = [&](const std::string& stem, int width, int height,
                        const std::function<void(int y, std::uint8_t*)>& display_row,
                        const std::function<void(int y, float*)>& linear_row) {
    if (options_.png) {
      const fs::path png = options_.dir / (stem + ".png");
      metrics::write_png_rows(png, width, height, display_row);
      written.push_back(png);
    }
    if (options_.exr) {
      const fs::path exr = options_.dir / (stem + ".exr");
      metrics::write_exr_rows(exr, width, height, linear_row,
                              views.linear_is_half() ? metrics::ExrPixels::half : metrics::ExrPixels::float32);
      written.push_back(exr);
    }
  };
  const int w = views.width(), h = views.height();
  auto view_pair = [&](const std::string& stem, std::size_t v) {
    write_pair(stem, w, h, [&](int y, std::uint8_t* rgb) { views.display_row(v, y, rgb); },
               [&](int y, float* rgb) { views.linear_row(v, y, rgb); });
  };

  if (kind_ == display::ViewSetKind::Single) {
    view_pair(single, 0);
    return written;
  }

  // Stereo is a 2 x 1 atlas (left eye left); light fields and grids are quilts. Pixels no tile
  // covers are black.
  const int count = static_cast<int>(views_);
  const auto atlas_width = std::size_t(layout_.width);
  write_pair(
      atlas_name(tag, ""), layout_.width, layout_.height,
      [&](int y, std::uint8_t* rgb) {
        std::fill(rgb, rgb + 3 * atlas_width, std::uint8_t{0});
        display::for_each_tile_in_row(layout_, count, y, [&](int view, int view_row, int x) {
          views.display_row(std::size_t(view), view_row, rgb + 3 * std::size_t(x));
        });
      },
      [&](int y, float* rgb) {
        std::fill(rgb, rgb + 3 * atlas_width, 0.0f);
        display::for_each_tile_in_row(layout_, count, y, [&](int view, int view_row, int x) {
          views.linear_row(std::size_t(view), view_row, rgb + 3 * std::size_t(x));
        });
      });

  if (options_.calibration) {
    // The panel shows display values, so those are what gets interleaved: the one place the
    // display quilt is held whole (as linear floats of the display bytes).
    display::RgbImage quilt(layout_.width, layout_.height);
    std::vector<std::uint8_t> row(3 * std::size_t(w));
    for (int y = 0; y < layout_.height; ++y)
      display::for_each_tile_in_row(layout_, count, y, [&](int view, int view_row, int x) {
        views.display_row(std::size_t(view), view_row, row.data());
        float* out = quilt.pixel(x, y);
        for (std::size_t i = 0; i < row.size(); ++i) out[i] = metrics::srgb8_decode(row[i]);
      });
    const display::RgbImage panel = display::interleave(quilt.view(), layout_, count,
                                                        display::lenticular_mapping(*options_.calibration));
    const fs::path png = options_.dir / (tagged(options_.stem, tag) + "_lenticular.png");
    const auto panel_width = std::size_t(panel.width());
    metrics::write_png_rows(png, panel.width(), panel.height(), [&](int y, std::uint8_t* rgb) {
      const float* p = panel.pixel(0, y);
      for (std::size_t i = 0; i < 3 * panel_width; ++i) rgb[i] = metrics::srgb8_encode(p[i]);
    });
    written.push_back(png);
  }

  if (options_.per_view)
    for (int i = 0; i < count; ++i)
      view_pair(tagged(display::indexed_view_name(i, count), tag), std::size_t(i));
  return written;
}

}  // namespace ddish::app
