// The files one frame of N views becomes, shared by `ddish render` and `ddish reference` so that
// an image and its reference always have the same names and layout:
//
//   single view      SINGLE.png + SINGLE.exr (the caller names it: frame_NNNN, reference)
//   light field/grid STEM_qs{cols}x{rows}a{aspect}.png + .exr: the quilt (display::quilt_file_name,
//                    view 0 bottom-left); the EXR is linear, so `ddish compare --views N` gives
//                    per-view errors of two quilts
//   stereo           STEM_sbs_qs2x1a{aspect}.png + .exr: the eyes side by side (left eye left,
//                    display::side_by_side), 2 × tile wide; named as a 2 × 1 quilt so compare
//                    splits it into the eyes too
//   per view         view_NN.png + .exr for every view (with per_view)
//   lenticular       STEM_lenticular.png: the panel image interleaved from the quilt's display
//                    values by a Looking Glass calibration (with a calibration, quilts only)
//
// With a frame tag (render --every) the multi-view names carry it: STEM_0003_qs8x6a0.75.png,
// view_07_0003.png, STEM_0003_lenticular.png. PNGs hold display values, EXRs linear radiance
// (16-bit halves for the rasterizer's views, which are halves already; 32-bit floats otherwise).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "display/calibration.h"
#include "display/view_set.h"
#include "metrics/image.h"
#include "raster/renderer.h"

namespace ddish::app {

struct OutputOptions {
  std::filesystem::path dir;
  std::string stem;  // names multi-view files: the scene file's stem
  bool per_view = false;
  std::optional<display::Calibration> calibration;
  // The file formats written (--formats): PNG holds the display values, EXR the linear ones. The
  // lenticular image of a calibration is a PNG and is written whenever a calibration is given.
  bool png = true;
  bool exr = true;
};

// One frame's views as the writer reads them, a row at a time (row 0 at the top), so that no
// atlas is ever composed whole: the quilt's rows are gathered from the views as they are encoded.
class FrameViews {
 public:
  virtual ~FrameViews() = default;
  virtual std::size_t count() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual void linear_row(std::size_t view, int y, float* rgb) const = 0;         // 3 * width
  virtual void display_row(std::size_t view, int y, std::uint8_t* rgb) const = 0;  // sRGB bytes
  // Whether every linear value is a 16-bit half already: the EXR then stores halves, exactly.
  virtual bool linear_is_half() const { return false; }
};

// The rasterizer's read-back views: linear radiance and the tone-mapping pass's display bytes.
// The linear pixels come from its RGBA16F target (Renderer::render), so its EXRs hold halves.
class RasterFrameViews final : public FrameViews {
 public:
  // Throws std::invalid_argument for no views or views of different sizes.
  explicit RasterFrameViews(std::span<const raster::ViewImage> views);
  std::size_t count() const override { return views_.size(); }
  int width() const override { return views_.front().width; }
  int height() const override { return views_.front().height; }
  void linear_row(std::size_t view, int y, float* rgb) const override;
  void display_row(std::size_t view, int y, std::uint8_t* rgb) const override;
  bool linear_is_half() const override { return true; }

 private:
  std::span<const raster::ViewImage> views_;
};

// Linear images with no tone curve (the reference): their display values are the clamped sRGB
// encoding of the linear values times `display_scale` (--exposure's 2^EV).
class LinearFrameViews final : public FrameViews {
 public:
  // Throws std::invalid_argument for no images or images of different sizes.
  explicit LinearFrameViews(std::span<const metrics::Image> images, float display_scale = 1.0f);
  std::size_t count() const override { return images_.size(); }
  int width() const override { return images_.front().width(); }
  int height() const override { return images_.front().height(); }
  void linear_row(std::size_t view, int y, float* rgb) const override;
  void display_row(std::size_t view, int y, std::uint8_t* rgb) const override;

 private:
  std::span<const metrics::Image> images_;
  float display_scale_ = 1.0f;
};

class FrameWriter {
 public:
  // Throws std::invalid_argument when a calibration is given for a set that makes no quilt, or
  // when neither PNG nor EXR is asked for.
  FrameWriter(const display::ViewSet& set, OutputOptions options);

  // Writes the frame; `single` names the file of a single-view set, `tag` (may be empty) is
  // added to the multi-view names. Returns the files written. Throws std::invalid_argument when
  // the views do not match the set. Each file is encoded from rows gathered from the views;
  // only the lenticular image (with a calibration) composes the display quilt in memory.
  std::vector<std::filesystem::path> write(const FrameViews& views, const std::string& single,
                                           const std::string& tag) const;

  // The quilt (or side-by-side) file name of the set, e.g. "cornell_box_qs8x6a0.75" + extension.
  std::string atlas_name(const std::string& tag, const std::string& extension) const;

 private:
  display::ViewSetKind kind_;
  display::QuiltLayout layout_;
  float aspect_;
  std::size_t views_;
  OutputOptions options_;
};

}  // namespace ddish::app
