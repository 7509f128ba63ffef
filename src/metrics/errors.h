// All the error figures ddish reports for one image against its reference, computed together
// (ddish compare, ddish reference --convergence, the benchmarks), and their text and JSON forms.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "metrics/image.h"

namespace ddish::metrics {

struct ImageErrors {
  double psnr = 0.0;    // dB on display values (psnr.h); +inf when identical
  double ssim = 0.0;    // mean SSIM on display luminance (ssim.h)
  double rmse = 0.0;    // linear (linear_error.h)
  double relmse = 0.0;  // linear, relative (linear_error.h)
};

// Throws std::invalid_argument when the sizes differ.
ImageErrors compute_errors(const Image& image, const Image& reference);

// A figure as ddish prints it: "inf" / "-inf" / "nan" for the non-finite values, otherwise
// `digits` significant digits.
std::string format_figure(double value, int digits = 6);

// {"psnr": ..., "ssim": ..., "rmse": ..., "relmse": ...}. JSON has no infinity, so a non-finite
// figure is written as the string "inf" (or "-inf", "nan"), the same word the text form uses.
nlohmann::ordered_json to_json(const ImageErrors& errors);

}  // namespace ddish::metrics
