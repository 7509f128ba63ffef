// A small HDR environment map for the GPU tracer's tests: 32 x 16 texels, a sky from a pale
// horizon to a deeper blue zenith, a sun of 3 x 2 texels 20 times brighter than the sky about
// 35 degrees up, and a dark brown ground below the horizon; turned 40 degrees about +Y and
// scaled by 1.5, so the rotation, the intensity and the importance sampling are all exercised.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment_map.h"

namespace ddish::trace_vk::test {

inline std::shared_ptr<const scene::EnvironmentMap> test_environment_map() {
  constexpr int kWidth = 32, kHeight = 16;
  std::vector<glm::vec3> texels;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float up = 1.0f - (y + 0.5f) / (kHeight / 2);  // 1 at the zenith, 0 at the horizon
      glm::vec3 c = y < kHeight / 2 ? glm::mix(glm::vec3(0.9f, 0.9f, 0.8f), glm::vec3(0.25f, 0.4f, 0.9f), up)
                                    : glm::vec3(0.12f, 0.08f, 0.05f);
      if (y >= 4 && y <= 5 && x >= 20 && x <= 22) c = glm::vec3(18.0f, 16.0f, 12.0f);
      texels.push_back(c);
    }
  return std::make_shared<const scene::EnvironmentMap>(
      scene::make_environment_map(kWidth, kHeight, std::move(texels), 40.0f, 1.5f, "test map"));
}

}  // namespace ddish::trace_vk::test
