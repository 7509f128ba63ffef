#include "app/frame_outputs.h"

#include <cstring>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "display/lenticular.h"
#include "display/quilt.h"
#include "display/stereo_output.h"
#include "metrics/color.h"
#include "metrics/image_io.h"
#include "raster/renderer.h"

namespace ddish::app {

namespace fs = std::filesystem;

namespace {

metrics::Image linear_image(const raster::ViewImage& v) {
  metrics::Image img(v.width, v.height);
  img.pixels() = v.linear;
  return img;
}

metrics::Image display_image(const raster::ViewImage& v) {
  metrics::Image img(v.width, v.height);
  for (std::size_t i = 0; i < v.display.size(); ++i) {
    const std::uint32_t p = v.display[i];
    img.pixels()[i] = {metrics::srgb8_decode(std::uint8_t(p & 0xffu)),
                       metrics::srgb8_decode(std::uint8_t((p >> 8) & 0xffu)),
                       metrics::srgb8_decode(std::uint8_t((p >> 16) & 0xffu))};
  }
  return img;
}

// A metrics::Image is a contiguous vector of glm::vec3, three packed floats a pixel: display/
// reads it in place.
display::ConstRgbView rgb_view(const metrics::Image& img) {
  return {img.width(), img.height(), &img.pixels().data()->x};
}

metrics::Image to_image(const display::RgbImage& rgb) {
  metrics::Image img(rgb.width(), rgb.height());
  std::memcpy(img.pixels().data(), rgb.data().data(), rgb.data().size() * sizeof(float));
  return img;
}

std::vector<display::ConstRgbView> rgb_views(const std::vector<metrics::Image>& images) {
  std::vector<display::ConstRgbView> views;
  views.reserve(images.size());
  for (const metrics::Image& img : images) views.push_back(rgb_view(img));
  return views;
}

std::string tagged(const std::string& name, const std::string& tag) {
  return tag.empty() ? name : name + "_" + tag;
}

}  // namespace

FrameImages frame_images(const raster::FrameOutput& frame) {
  FrameImages images;
  for (const raster::ViewImage& v : frame.views) {
    images.linear.push_back(linear_image(v));
    images.display.push_back(display_image(v));
  }
  return images;
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
}

std::string FrameWriter::atlas_name(const std::string& tag, const std::string& extension) const {
  const std::string name = tagged(options_.stem, tag);
  if (kind_ == display::ViewSetKind::Stereo)
    return display::quilt_file_name(name + "_sbs", layout_, aspect_, extension);
  return display::quilt_file_name(name, layout_, aspect_, extension);
}

std::vector<fs::path> FrameWriter::write(const FrameImages& images, const std::string& single,
                                         const std::string& tag) const {
  if (images.linear.size() != views_ || images.display.size() != views_)
    throw std::invalid_argument(fmt::format("a frame of {} views got {} images", views_,
                                            images.linear.size()));
  std::vector<fs::path> written;
  auto write_pair = [&](const std::string& stem, const metrics::Image& display,
                        const metrics::Image& linear) {
    const fs::path png = options_.dir / (stem + ".png");
    const fs::path exr = options_.dir / (stem + ".exr");
    metrics::write_png(png, display);
    metrics::write_exr(exr, linear);
    written.push_back(png);
    written.push_back(exr);
  };

  if (kind_ == display::ViewSetKind::Single) {
    write_pair(single, images.display.front(), images.linear.front());
    return written;
  }

  if (kind_ == display::ViewSetKind::Stereo) {
    write_pair(atlas_name(tag, ""),
               to_image(display::side_by_side(rgb_view(images.display[0]), rgb_view(images.display[1]))),
               to_image(display::side_by_side(rgb_view(images.linear[0]), rgb_view(images.linear[1]))));
  } else {
    const std::vector<display::ConstRgbView> display_views = rgb_views(images.display);
    const display::RgbImage display_quilt = display::compose_quilt(display_views, layout_);
    const std::vector<display::ConstRgbView> linear_views = rgb_views(images.linear);
    write_pair(atlas_name(tag, ""), to_image(display_quilt),
               to_image(display::compose_quilt(linear_views, layout_)));
    if (options_.calibration) {
      // The panel shows display values, so those are what gets interleaved.
      const display::RgbImage panel =
          display::interleave(display_quilt.view(), layout_, static_cast<int>(views_),
                              display::lenticular_mapping(*options_.calibration));
      const fs::path png = options_.dir / (tagged(options_.stem, tag) + "_lenticular.png");
      metrics::write_png(png, to_image(panel));
      written.push_back(png);
    }
  }

  if (options_.per_view) {
    const int count = static_cast<int>(views_);
    for (int i = 0; i < count; ++i) {
      const auto v = static_cast<std::size_t>(i);
      write_pair(tagged(display::indexed_view_name(i, count), tag), images.display[v],
                 images.linear[v]);
    }
  }
  return written;
}

}  // namespace ddish::app
