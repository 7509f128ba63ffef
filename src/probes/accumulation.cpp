#include "probes/accumulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::probes {

void check_hysteresis(float alpha) {
  if (!(alpha >= 0.0f && alpha < 1.0f))
    throw std::invalid_argument("hysteresis must be in [0, 1), got " + std::to_string(alpha));
}

float blend_weight(std::uint32_t k, float alpha) {
  if (k == 0) return 1.0f;  // defensive: the first update always replaces the (zero) start
  return std::max(1.0f / float(k), 1.0f - alpha);
}

}  // namespace ddish::probes
