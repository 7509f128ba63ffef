// Which forward-shader features a scene needs, chosen from scene::SceneFeatures through the
// scene's RenderPlan (scene/features.h) and passed to the shaders (forward_variant.glsl) as
// specialization constants 0..5, so a scene without glossy materials runs no specular-probe
// code, one without punctual lights neither evaluates lights nor renders shadow maps, one
// without textures samples none.
#pragma once

#include <vector>

#include <vulkan/vulkan.h>

namespace ddish::scene {
struct RenderPlan;
}

namespace ddish::raster {

struct ShaderVariant {
  bool direct_lights = true;    // constant 0
  bool shadows = true;          // constant 1
  bool textures = true;         // constant 2
  bool specular_probes = true;  // constant 3
  bool probes = true;           // constant 4: false renders without indirect light
  bool emission = true;         // constant 5

  std::vector<VkBool32> constants() const {
    return {direct_lights, shadows, textures, specular_probes, probes, emission};
  }
};

ShaderVariant variant_for(const scene::RenderPlan& plan);

}  // namespace ddish::raster
