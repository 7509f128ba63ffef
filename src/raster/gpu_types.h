// C++ mirrors of the structures the rasterizer's shaders read (shaders/raster_common.glsl,
// shaders/forward.frag). Every member is a vec4 or mat4 so std140 and std430 agree with the C++
// layout without padding rules; the static_asserts keep both sides honest.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace ddish::raster {

// Push constants of every draw (forward, shadow and visibility): 128 bytes, the most every
// device has.
struct DrawConstants {
  glm::mat4 model{1.0f};
  glm::vec4 normal_matrix[3]{};  // columns of inverse-transpose(mat3(model)); [0].w: handedness
  std::uint32_t view_index = 0;  // forward: views[]; shadow: shadow_layers[]
  std::uint32_t material = 0;
  // The visibility pass (raster/visibility_pass.h): the scene instance drawn, and the index of
  // the draw's first triangle in GpuMeshes' index buffer (pushed with every draw).
  std::uint32_t instance = 0;
  std::uint32_t first_triangle = 0;
};
static_assert(sizeof(DrawConstants) == 128);

// Builds the per-instance constants: the normal matrix is computed once per instance, not per
// vertex. A mirroring transform (det < 0) flips the tangent handedness, as glTF requires.
DrawConstants draw_constants(const glm::mat4& model, std::uint32_t view_index,
                             std::uint32_t material);

struct ViewData {
  glm::mat4 view_proj{1.0f};
  glm::vec4 eye{0.0f};
};
static_assert(sizeof(ViewData) == 80);

struct FrameData {
  glm::vec4 environment{0.0f};
  glm::uvec4 counts{0u};         // x: lights, y: shadow layers, z: views
  // x: 1 / shadow map size, y: PCF tap spacing in texels, z: 1 where the comparison sampler
  // filters bilinearly (the shader then reads a 1-texel-spaced 3x3 grid of taps as 4 taps)
  glm::vec4 shadow_params{0.0f};
};
static_assert(sizeof(FrameData) == 48);

enum class LightKind : std::uint32_t { directional = 0, point = 1, spot = 2 };

struct LightData {
  glm::vec4 position_range{0.0f};
  glm::vec4 direction_type{0.0f};
  glm::vec4 radiant{0.0f};
  glm::vec4 spot_shadow{0.0f, 0.0f, -1.0f, 0.0f};
};
static_assert(sizeof(LightData) == 64);

struct ShadowLayerData {
  glm::mat4 light_view_proj{1.0f};
  glm::vec4 params{0.0f};  // x: depth bias, y: normal offset (world units)
};
static_assert(sizeof(ShadowLayerData) == 80);

// Texture slots as bits of MaterialData::alpha.z (forward.frag's has_texture).
enum TextureBit : std::uint32_t {
  kBaseColorBit = 1u,
  kMetallicRoughnessBit = 2u,
  kNormalBit = 4u,
  kOcclusionBit = 8u,
  kEmissiveBit = 16u,
};

// Texture slots in MaterialData::uv_rows' order (bindings 1..5 of the material set).
inline constexpr std::uint32_t kMaterialSlots = 5;

struct MaterialData {
  glm::vec4 base_color{1.0f};
  glm::vec4 emission{0.0f};  // rgb: emissiveFactor × strength; w: 1 = KHR_materials_unlit
  glm::vec4 params{0.0f};  // metallic, roughness, normal scale, occlusion strength
  glm::vec4 alpha{0.0f};   // cutoff, 1 = MASK, texture bits, 1 = BLEND
  // Per slot s: rows 2s and 2s+1 of its KHR_texture_transform (scene::TextureTransform::row0/1),
  // uv' = (dot(row0.xyz, (uv, 1)), dot(row1.xyz, (uv, 1))); row0.w is the UV set (0 or 1).
  glm::vec4 uv_rows[2 * kMaterialSlots]{};
  // rgb: the dielectric layer's F0 (KHR_materials_ior, KHR_materials_specular's colour), w: the
  // layer's weight (specularFactor); 0.04 and 1 by default.
  glm::vec4 dielectric{0.04f, 0.04f, 0.04f, 1.0f};
};
static_assert(sizeof(MaterialData) == 80 + 32 * kMaterialSlots);

}  // namespace ddish::raster
