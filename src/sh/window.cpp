#include "sh/window.h"

#include <cmath>

namespace ddish::sh {

BandScales window_factors(Window window, float width) {
  BandScales w{1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
  if (window == Window::kNone || !(width > 0.0f)) return w;
  const double pi = 3.14159265358979323846;
  for (int l = 1; l <= kMaxOrder; ++l) {
    const double x = double(l) / double(width);
    double f = 0.0;
    if (x < 1.0) f = window == Window::kHann ? 0.5 * (1.0 + std::cos(pi * x))
                                             : std::sin(pi * x) / (pi * x);
    w[static_cast<std::size_t>(l)] = float(f);
  }
  return w;
}

ShRgb apply_window(const ShRgb& sh, Window window, float width) {
  return convolve_bands(sh, window_factors(window, width));
}

}  // namespace ddish::sh
