#include "metrics/linear_error.h"

#include <cmath>

#include "metrics/channel_mean.h"

namespace ddish::metrics {

double rmse(const Image& image, const Image& reference) {
  return std::sqrt(channel_mean(image, reference,
                                [](double& sum, const glm::vec3& a, const glm::vec3& b) {
                                  glm::dvec3 d = glm::dvec3(a) - glm::dvec3(b);
                                  sum += glm::dot(d, d);
                                }));
}

double relative_mse(const Image& image, const Image& reference, double epsilon) {
  return channel_mean(image, reference,
                      [epsilon](double& sum, const glm::vec3& a, const glm::vec3& b) {
                        for (int c = 0; c < 3; ++c) {
                          double d = double(a[c]) - double(b[c]);
                          double r = double(b[c]);
                          sum += d * d / (r * r + epsilon);
                        }
                      });
}

}  // namespace ddish::metrics
