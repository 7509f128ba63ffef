// Helpers shared by the net tests: radiance-like probes (SH of non-negative functions), frames.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "sh/projection.h"
#include "sh/sh_rgb.h"

namespace ddish::net::test {

inline glm::vec3 random_direction(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float z = 1.0f - 2.0f * u(rng);
  const float phi = 6.2831853f * u(rng);
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// The SH of a non-negative radiance: `lobes` point sources of random colour and direction plus
// an ambient term, scaled by `brightness`. Every coefficient keeps the radiance bound
// |c_lm| <= sqrt(2l+1) c_00 per channel that the compact encoding relies on.
inline sh::ShRgb radiance_probe(std::mt19937_64& rng, int order, float brightness, int lobes = 3,
                                float ambient = 0.3f) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  sh::ShRgb s(order);
  s[0] = glm::vec3(ambient * brightness * 3.5449077f);  // ambient L: c_00 = sqrt(4π) L
  for (int k = 0; k < lobes; ++k)
    s += sh::project_direction(random_direction(rng),
                               brightness * glm::vec3(u(rng), u(rng), u(rng)), order);
  return s;
}

inline std::vector<glm::vec3> coefficients_of(const sh::ShRgb& s) {
  return {s.c.begin(), s.c.begin() + s.count()};
}

}  // namespace ddish::net::test
