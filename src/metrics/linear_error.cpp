#include "metrics/linear_error.h"

#include <cmath>

namespace ddish::metrics {

double rmse(const Image& image, const Image& reference) {
  require_same_size(image, reference);
  if (image.empty()) return 0.0;
  double sum = 0.0;
  const auto& a = image.pixels();
  const auto& b = reference.pixels();
  for (std::size_t i = 0; i < a.size(); ++i) {
    glm::dvec3 d = glm::dvec3(a[i]) - glm::dvec3(b[i]);
    sum += glm::dot(d, d);
  }
  return std::sqrt(sum / (3.0 * static_cast<double>(a.size())));
}

double relative_mse(const Image& image, const Image& reference, double epsilon) {
  require_same_size(image, reference);
  if (image.empty()) return 0.0;
  double sum = 0.0;
  const auto& a = image.pixels();
  const auto& b = reference.pixels();
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      double d = double(a[i][c]) - double(b[i][c]);
      double r = double(b[i][c]);
      sum += d * d / (r * r + epsilon);
    }
  }
  return sum / (3.0 * static_cast<double>(a.size()));
}

}  // namespace ddish::metrics
