#include "probes/fibonacci.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/quaternion.hpp>

namespace ddish::probes {

glm::vec3 fibonacci_direction(std::uint32_t i, std::uint32_t n) {
  // Double precision for the azimuth: i / phi loses the fractional part in float beyond ~1e6.
  const double golden = std::numbers::phi;
  double z = 1.0 - (2.0 * double(i) + 1.0) / double(n);
  double frac = double(i) / golden - std::floor(double(i) / golden);
  double phi = 2.0 * std::numbers::pi * frac;
  double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

glm::mat3 random_rotation(trace::Sampler& sampler) {
  const float two_pi = 2.0f * std::numbers::pi_v<float>;
  float u1 = sampler.next1d();
  float u2 = sampler.next1d();
  float u3 = sampler.next1d();
  float a = std::sqrt(1.0f - u1), b = std::sqrt(u1);
  glm::quat q(b * std::cos(two_pi * u3),  // w
              a * std::sin(two_pi * u2), a * std::cos(two_pi * u2), b * std::sin(two_pi * u3));
  return glm::mat3_cast(glm::normalize(q));
}

}  // namespace ddish::probes
