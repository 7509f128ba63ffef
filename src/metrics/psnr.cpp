#include "metrics/psnr.h"

#include <cmath>
#include <limits>

#include "metrics/color.h"

namespace ddish::metrics {

double display_mse(const Image& image, const Image& reference) {
  require_same_size(image, reference);
  if (image.empty()) return 0.0;
  // Accumulated in double: a 4K image has 25 M terms, far more than float keeps exactly.
  double sum = 0.0;
  const auto& a = image.pixels();
  const auto& b = reference.pixels();
  for (std::size_t i = 0; i < a.size(); ++i) {
    glm::dvec3 d = glm::dvec3(display_value(a[i])) - glm::dvec3(display_value(b[i]));
    sum += glm::dot(d, d);
  }
  return sum / (3.0 * static_cast<double>(a.size()));
}

double psnr(const Image& image, const Image& reference) {
  double mse = display_mse(image, reference);
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  // peak = 1 (display values are in [0, 1]), so PSNR = 10 log10(1 / MSE).
  return -10.0 * std::log10(mse);
}

}  // namespace ddish::metrics
