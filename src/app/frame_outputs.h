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
// view_07_0003.png, STEM_0003_lenticular.png. PNGs hold display values, EXRs linear radiance.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "display/calibration.h"
#include "display/view_set.h"
#include "metrics/image.h"

namespace ddish::raster {
struct FrameOutput;
}

namespace ddish::app {

struct OutputOptions {
  std::filesystem::path dir;
  std::string stem;  // names multi-view files: the scene file's stem
  bool per_view = false;
  std::optional<display::Calibration> calibration;
};

// One frame's images, one per view in view order, all tile-sized.
struct FrameImages {
  std::vector<metrics::Image> linear;
  // Values whose clamp + sRGB encoding (metrics::write_png) gives the display pixels exactly.
  std::vector<metrics::Image> display;
};

// The rasterizer's read-back views as images (display pixels decoded back to linear so that
// write_png reproduces the bytes the tone-mapping pass wrote).
FrameImages frame_images(const raster::FrameOutput& frame);

class FrameWriter {
 public:
  // Throws std::invalid_argument when a calibration is given for a set that makes no quilt.
  FrameWriter(const display::ViewSet& set, OutputOptions options);

  // Writes the frame; `single` names the file of a single-view set, `tag` (may be empty) is
  // added to the multi-view names. Returns the files written. Throws std::invalid_argument when
  // the images do not match the set.
  std::vector<std::filesystem::path> write(const FrameImages& images, const std::string& single,
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
