// Structural similarity (Wang, Bovik, Sheikh, Simoncelli 2004, "Image quality assessment: from
// error visibility to structural similarity") on the luminance of the display values:
// Y = 0.2126 R' + 0.7152 G' + 0.0722 B' of the clamped, sRGB-encoded channels (color.h).
//
// Local statistics use the paper's 11 × 11 circular-symmetric Gaussian window, sigma = 1.5,
// normalised to sum 1; K1 = 0.01, K2 = 0.03, dynamic range L = 1, so C1 = (K1 L)^2 and
// C2 = (K2 L)^2. The means, variances and covariance are the window-weighted (biased) moments.
//
// Border handling: the window is evaluated only where it lies entirely inside the image (the
// "valid" positions, as in the paper's reference implementation), so an image of W × H pixels
// has (W − 10) × (H − 10) SSIM values and the result is their mean; no padding is invented.
// An image narrower or shorter than 11 pixels uses the centre of the Gaussian truncated to the
// image along that axis (still renormalised to sum 1); a 2 × 2 image therefore has one window
// with four equal weights.
#pragma once

#include "metrics/image.h"

namespace ddish::metrics {

struct SsimParams {
  int window = 11;      // window size in pixels (odd)
  double sigma = 1.5;   // Gaussian standard deviation in pixels
  double k1 = 0.01;
  double k2 = 0.03;
  double range = 1.0;   // L: display values span [0, 1]
};

// Mean SSIM over the valid window positions; 1 for identical images. Throws
// std::invalid_argument when the sizes differ or an image is empty.
double ssim(const Image& image, const Image& reference, const SsimParams& params = {});

}  // namespace ddish::metrics
