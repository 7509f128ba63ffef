// Peak signal-to-noise ratio on display values: both images are clamped to [0, 1] and
// sRGB-encoded (color.h), the mean squared error is taken over every pixel and all three
// channels, and PSNR = 10 log10(peak^2 / MSE) with peak 1. Display values are what a viewer
// sees, so a PSNR does not depend on how bright the unclamped linear values are.
#pragma once

#include "metrics/image.h"

namespace ddish::metrics {

// Mean squared error of the display values over R, G and B (the MSE behind psnr()).
double display_mse(const Image& image, const Image& reference);

// PSNR in dB; +infinity when the display values are identical (MSE = 0). Throws
// std::invalid_argument when the sizes differ.
double psnr(const Image& image, const Image& reference);

}  // namespace ddish::metrics
