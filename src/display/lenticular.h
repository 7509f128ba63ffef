// Lenticular interleaving: the panel image a Looking Glass shows, built from a quilt. Each
// subpixel of the panel lies under some part of a slanted lenticule and is seen from one
// direction only; the calibration says which view that is, and the subpixel takes its value
// from that view's tile at the same place on the screen.
//
// The mapping is the one Looking Glass publishes in its lenticular shaders (HoloPlay Core /
// holoplay.js), with the calibration turned into shader terms as their SDKs do:
//   pitch' = pitch · (screenW / DPI) · cos(atan(1 / slope))   lenticules across the screen width
//            (the lenticules are slanted, so along a row they are 1/cos further apart)
//   tilt   = screenH / (screenW · slope), negated when flipImageX
//   subp   = 1 / (3 · screenW)                                 one subpixel in screen units
// For the panel pixel in column x and row r (row 0 at the top), u = (x + ½) / screenW and
// v = 1 − (r + ½) / screenH (v grows upwards, as in the shaders' texture coordinates); subpixel
// sample s ∈ {0, 1, 2} (red, green, blue; red and blue swap when flipSubp) sees
//   phase = fract((u + s · subp + v · tilt) · pitch' − center)
//   phase ← 1 − phase when invView
//   view  = min(floor(phase · N), N − 1)                       N = views in the quilt
// and reads that view at (u, v) — mirrored to 1 − u / 1 − v when flipImageX / flipImageY — with
// bilinear filtering inside the tile. (flipImageX also mirrors u in the phase, as the panel is
// mounted mirrored.)
#pragma once

#include "display/calibration.h"
#include "display/quilt_layout.h"
#include "display/rgb_image.h"

namespace ddish::display {

// The calibration in shader terms (see above).
struct LenticularMapping {
  int screen_width = 0;
  int screen_height = 0;
  double pitch = 0.0;   // pitch'
  double tilt = 0.0;
  double subp = 0.0;
  double center = 0.0;
  bool inv_view = false;
  bool flip_x = false;
  bool flip_y = false;
  int red_sample = 0;   // which subpixel sample feeds red (2 when flipSubp)
  int blue_sample = 2;  // which feeds blue (0 when flipSubp)
};

LenticularMapping lenticular_mapping(const Calibration& calibration);

// The phase in [0, 1) across the view cone seen by sample `sample` (0..2) of panel pixel
// (x, row), invView applied.
double subpixel_phase(const LenticularMapping& m, int x, int row, int sample);

// The view (0..views−1) that channel `channel` (0 red, 1 green, 2 blue) of panel pixel (x, row)
// shows.
int subpixel_view(const LenticularMapping& m, int x, int row, int channel, int views);

// One axis of the bilinear tap a panel pixel takes inside a tile: texels i0 and i1 (tile
// coordinates, rows from the top) weighed 1 − f and f. It depends on the panel column (x) or row
// alone, and on the tile size, never on the view; interleave() samples through these, and the GPU
// pass (display/gpu_compositor.h) reads them from tables so that both take the same texels with
// the same weights.
struct BilinearTap {
  int i0 = 0;
  int i1 = 0;
  float f = 0.0f;
};
BilinearTap tile_tap_x(const LenticularMapping& m, int x, int tile_width);
BilinearTap tile_tap_y(const LenticularMapping& m, int row, int tile_height);

// The screen_width × screen_height panel image. `views` is how many quilt cells hold views
// (≤ layout.cells()). Throws std::invalid_argument when the quilt is not layout-sized or views
// is out of range.
RgbImage interleave(ConstRgbView quilt, const QuiltLayout& layout, int views,
                    const LenticularMapping& mapping);

}  // namespace ddish::display
