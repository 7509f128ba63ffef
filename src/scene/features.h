// What a scene holds (SceneFeatures) and what the renderer can therefore leave out for it
// (RenderPlan): a scene pays only for the passes and shader features it uses.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/aabb.h"
#include "scene/scene.h"

namespace ddish::scene {

// A material is glossy when its roughness factor is below this, or when a metallic-roughness
// texture may make it so (texels are not inspected, so `ddish info`, which does not decode
// textures, and the renderer reach the same plan). At roughness 0.5 the GGX lobe (alpha =
// roughness^2 = 0.25) is narrow enough that the diffuse SH term alone visibly misses highlights.
inline constexpr float kGlossyRoughness = 0.5f;
// A material counts as a metal when its metallic factor is at least this.
inline constexpr float kMetalThreshold = 0.5f;

// Counts are over the materials that instances use (the default material included when a
// mesh has none), so materials no instance draws do not switch features on.
struct SceneFeatures {
  std::size_t triangles = 0;  // after instancing
  std::size_t instances = 0;
  std::size_t meshes = 0;
  std::size_t materials_used = 0;
  std::size_t textures_used = 0;

  std::size_t glossy_materials = 0;
  std::size_t metal_materials = 0;
  std::size_t textured_materials = 0;  // any texture slot
  std::size_t normal_mapped_materials = 0;
  std::size_t masked_materials = 0;   // alphaMode MASK
  std::size_t blended_materials = 0;  // alphaMode BLEND
  std::size_t double_sided_materials = 0;
  std::size_t emissive_materials = 0;  // emissiveFactor × strength > 0
  std::size_t second_uv_materials = 0;          // a texture on TEXCOORD_1
  std::size_t texture_transform_materials = 0;  // a texture with a KHR_texture_transform
  std::size_t dielectric_materials = 0;  // KHR_materials_ior / _specular other than glTF's default
  std::size_t vertex_colored_meshes = 0;  // instanced meshes with COLOR_0
  std::size_t skinned_meshes = 0;  // deformed meshes (Scene::deformed) that a skin moves
  std::size_t morphed_meshes = 0;  // deformed meshes with morph targets

  std::size_t directional_lights = 0;
  std::size_t point_lights = 0;
  std::size_t spot_lights = 0;
  std::size_t cameras = 0;
  std::size_t animations = 0;
  double animation_duration = 0.0;  // seconds

  glm::vec3 environment{0.0f};  // the uniform radiance
  bool environment_map = false;  // an equirectangular map (--environment)
  Aabb bounds;  // at the current pose

  std::size_t punctual_lights() const { return directional_lights + point_lights + spot_lights; }
  bool has_environment() const {
    return environment_map || glm::any(glm::greaterThan(environment, glm::vec3(0.0f)));
  }
};

SceneFeatures analyze(const Scene& scene);

// One thing the renderer leaves out for this scene, and why.
struct PlanItem {
  std::string what;
  std::string why;
};

// The switches the renderer and the probe tracer read; `left_out` explains every false one.
struct RenderPlan {
  bool direct_lights = true;     // punctual light evaluation in the forward pass
  bool shadow_maps = true;       // shadow maps for directional and spot lights
  bool point_shadows = true;     // cube shadow maps for point lights
  bool specular_probes = true;   // GGX zonal-harmonic specular term from the probes
  bool texture_sampling = true;  // material textures bound and sampled
  bool normal_mapping = true;
  bool alpha_test = true;   // discard below alphaCutoff (MASK)
  bool alpha_blend = true;  // sorted transparent pass (BLEND)
  bool emission = true;     // emissive term in shading and in probe rays
  bool environment = true;  // sky radiance for rays that escape
  bool animation = true;    // per-frame pose, acceleration-structure refits, shadow redraws
  std::vector<PlanItem> left_out;
};

RenderPlan make_plan(const SceneFeatures& features);

}  // namespace ddish::scene
