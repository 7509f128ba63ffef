#include "raster/anisotropy.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ddish::raster {

void check_anisotropy(int requested) {
  if (requested < 0 || requested > kMaxAnisotropyOption)
    throw std::invalid_argument("anisotropy must be 0 (automatic: 8 on GPUs, off on CPU devices), "
                                "1 (off) or a maximum up to " +
                                std::to_string(kMaxAnisotropyOption) + ", not " +
                                std::to_string(requested));
}

float resolve_anisotropy(int requested, gpu::DeviceType type, bool feature, float device_limit) {
  check_anisotropy(requested);
  if (!feature) return 1.0f;
  const int wanted = requested != kAutomaticAnisotropy ? requested
                     : type == gpu::DeviceType::cpu    ? 1
                                                       : 8;
  return std::max(1.0f, std::min(static_cast<float>(wanted), device_limit));
}

}  // namespace ddish::raster
