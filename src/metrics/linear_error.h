// Errors on linear values, where energy is compared rather than appearance: the root mean
// squared error and the relative mean squared error (relMSE, the usual figure for Monte-Carlo
// renderings because it weighs dark and bright regions alike). Both average over every pixel
// and all three channels; the second argument is the reference.
#pragma once

#include "metrics/image.h"

namespace ddish::metrics {

// epsilon in relMSE's denominator: keeps black reference pixels from dividing by zero and sets
// the scale below which an error counts as absolute (0.01 = a reference value of 0.1).
inline constexpr double kRelMseEpsilon = 0.01;

// sqrt(mean((a - b)^2)) over pixels and R, G, B.
double rmse(const Image& image, const Image& reference);

// mean((a - b)^2 / (b^2 + epsilon)) over pixels and R, G, B, with b the reference.
double relative_mse(const Image& image, const Image& reference,
                    double epsilon = kRelMseEpsilon);

}  // namespace ddish::metrics
