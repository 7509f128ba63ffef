#include "metrics/psnr.h"

#include <cmath>
#include <limits>

#include "metrics/channel_mean.h"
#include "metrics/color.h"

namespace ddish::metrics {

double display_mse(const Image& image, const Image& reference) {
  return channel_mean(image, reference, [](double& sum, const glm::vec3& a, const glm::vec3& b) {
    glm::dvec3 d = glm::dvec3(display_value(a)) - glm::dvec3(display_value(b));
    sum += glm::dot(d, d);
  });
}

double psnr(const Image& image, const Image& reference) {
  double mse = display_mse(image, reference);
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  // peak = 1 (display values are in [0, 1]), so PSNR = 10 log10(1 / MSE).
  return -10.0 * std::log10(mse);
}

}  // namespace ddish::metrics
