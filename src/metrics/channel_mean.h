// The loop the per-pixel error metrics share: check the sizes, then average what `add` sums over
// every pixel pair into one double accumulator, divided by the number of channel values.
#pragma once

#include <cstddef>

#include "metrics/image.h"

namespace ddish::metrics {

// require_same_size, then sum / (3 * pixels) where `add(sum, a, b)` adds the terms of one pixel
// of `image` (a) and of `reference` (b) to `sum`, in pixel order; 0 for empty images.
// Accumulated in double: a 4K image has 25 M terms, far more than float keeps exactly.
template <class AddPixel>
double channel_mean(const Image& image, const Image& reference, AddPixel add) {
  require_same_size(image, reference);
  if (image.empty()) return 0.0;
  double sum = 0.0;
  const auto& a = image.pixels();
  const auto& b = reference.pixels();
  for (std::size_t i = 0; i < a.size(); ++i) add(sum, a[i], b[i]);
  return sum / (3.0 * static_cast<double>(a.size()));
}

}  // namespace ddish::metrics
