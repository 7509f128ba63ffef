// Shared by the command-line tests of scenes lit only by the default sky (radiance 1): which
// pixels show the scene's grey (albedo 0.5) objects, and what they and the sky around them read.
#pragma once

#include <algorithm>
#include <cstddef>

#include <glm/glm.hpp>

#include "metrics/image.h"

namespace sky_coverage {

inline float mean(const glm::vec3& c) { return (c.r + c.g + c.b) / 3.0f; }

// An object's pixels: darker than halfway between it (about 0.5) and the sky (1).
inline bool on_object(const glm::vec3& c) { return mean(c) < 0.75f; }

struct Coverage {
  double fraction = 0.0;  // of the image's pixels on an object
  double object_mean = 0.0;
  double background_mean = 0.0;
};

inline Coverage coverage(const ddish::metrics::Image& img) {
  Coverage c;
  std::size_t n = 0;
  for (const glm::vec3& p : img.pixels()) {
    if (on_object(p)) {
      ++n;
      c.object_mean += mean(p);
    } else {
      c.background_mean += mean(p);
    }
  }
  const std::size_t all = img.pixels().size();
  c.fraction = double(n) / double(all);
  c.object_mean /= double(std::max<std::size_t>(n, 1));
  c.background_mean /= double(std::max<std::size_t>(all - n, 1));
  return c;
}

}  // namespace sky_coverage
