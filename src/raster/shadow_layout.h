// Where each punctual light's shadow map sits in the shadow-map array and how it projects:
// directional lights get cascades fitted to the view frustum, spot lights one perspective map
// that covers the cone, point lights six 90-degree faces of a cube (+X, -X, +Y, -Y, +Z, -Z, the
// order forward.frag selects them in). Plain math on the scene model, no Vulkan: the renderer
// uploads what this computes, and the tests check it on the CPU.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/gpu_types.h"
#include "scene/aabb.h"

namespace ddish::scene {
struct Light;
struct View;
}  // namespace ddish::scene

namespace ddish::raster {

struct ShadowSettings {
  std::uint32_t map_size = 1024;  // texels per side of every layer
  int cascades = 3;               // per directional light, 1..4
  float split_lambda = 0.6f;      // blend of logarithmic (1) and uniform (0) cascade splits
  bool enabled = true;            // directional and spot maps (RenderPlan::shadow_maps)
  bool point_shadows = true;      // false: point lights stay unshadowed
};

struct ShadowLayout {
  std::vector<LightData> lights;          // one per scene light, shadow fields filled in
  std::vector<ShadowLayerData> layers;    // every layer of every light, in order
};

// Lights with their shadow layers for this frame. `views` are the views being rendered (the
// cascades cover the first view's frustum, clipped to the scene bounds); `bounds` encloses
// every shadow caster.
ShadowLayout layout_shadows(std::span<const scene::Light> lights, std::span<const scene::View> views,
                            const scene::Aabb& bounds, const ShadowSettings& settings);

// The camera-space distances where cascades end: count values in (znear, zfar], increasing.
std::vector<float> cascade_splits(float znear, float zfar, int count, float lambda);

}  // namespace ddish::raster
