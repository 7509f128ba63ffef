// Deringing windows: per-band factors w_l that taper the higher bands of a truncated SH
// expansion, trading a little blur for much less ringing (negative lobes opposite a bright
// light, which show as dark halos in irradiance and specular lookups).
//
// Both windows depend on a width W > 0 (bands l >= W are zeroed); the usual choice is
// W = order + 1, a smaller W filters harder.
//   Hann:    w_l = (1 + cos(pi l / W)) / 2
//   Lanczos: w_l = sinc(l / W) = sin(pi l / W) / (pi l / W)      (Lanczos sigma factors)
// w_0 = 1 always, so the mean (and the irradiance of a constant environment) is unchanged.
#pragma once

#include "sh/convolution.h"
#include "sh/sh_rgb.h"

namespace ddish::sh {

enum class Window { kNone, kHann, kLanczos };

BandScales window_factors(Window window, float width);
// Multiplies band l by window_factors(window, width)[l].
ShRgb apply_window(const ShRgb& sh, Window window, float width);

}  // namespace ddish::sh
