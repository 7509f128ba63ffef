// The forward pass's material inputs, shared by the shading (forward_main.glsl) and the depth
// prepass of alpha-masked materials (forward_depth_masked.frag), so that both decide a masked
// pixel's coverage from the same base colour: the feature switches (forward_variant.glsl), the
// material set and its textures, the UV sets and COLOR_0.
#ifndef DDISH_FORWARD_MATERIAL_GLSL
#define DDISH_FORWARD_MATERIAL_GLSL

#define MATERIAL_SET 3  // after set 0 (frame), PROBE_SET 1 and BRDF_SET 2

#include "forward_variant.glsl"

layout(set = MATERIAL_SET, binding = 0) uniform MaterialData {
  vec4 base_color;
  vec4 emission;   // rgb: emissiveFactor × strength; w: 1 = KHR_materials_unlit
  vec4 params;     // x: metallic, y: roughness, z: normal scale, w: occlusion strength
  vec4 alpha;      // x: cutoff, y: 1 = MASK, z: bit set of bound textures, w: 1 = BLEND
  // Slot s (base colour, metallic-roughness, normal, occlusion, emissive): rows 2s, 2s+1 of its
  // KHR_texture_transform; row 2s's w is the UV set (raster/gpu_types.h).
  vec4 uv_rows[10];
  vec4 dielectric;  // rgb: the dielectric layer's F0, w: its weight (KHR_materials_ior, _specular)
} material;
layout(set = MATERIAL_SET, binding = 1) uniform sampler2D base_color_tex;
layout(set = MATERIAL_SET, binding = 2) uniform sampler2D metallic_roughness_tex;
layout(set = MATERIAL_SET, binding = 3) uniform sampler2D normal_tex;
layout(set = MATERIAL_SET, binding = 4) uniform sampler2D occlusion_tex;
layout(set = MATERIAL_SET, binding = 5) uniform sampler2D emissive_tex;

layout(location = 2) in vec4 in_uv;     // xy: TEXCOORD_0, zw: TEXCOORD_1
layout(location = 5) in vec4 in_color;  // COLOR_0

bool has_texture(uint bit) { return kTextures && (uint(material.alpha.z) & bit) != 0u; }

// The coordinate texture slot s reads: its UV set, then its KHR_texture_transform (as the path
// tracer's trace::slot_uv).
vec2 slot_uv(int s) {
  const vec4 r0 = material.uv_rows[2 * s];
  const vec4 r1 = material.uv_rows[2 * s + 1];
  const vec3 uv = vec3(r0.w > 0.5 ? in_uv.zw : in_uv.xy, 1.0);
  return vec2(dot(r0.xyz, uv), dot(r1.xyz, uv));
}

// The base colour: factor, COLOR_0 (glTF: both multiply the texture, as in trace/surface.cpp)
// and texture.
vec4 material_base_color() {
  vec4 base = material.base_color * in_color;
  if (has_texture(1u)) base *= texture(base_color_tex, slot_uv(0));
  return base;
}

// A MASK material's pixel below its alpha cutoff shows what is behind it.
bool masked_out(float alpha) { return material.alpha.y > 0.5 && alpha < material.alpha.x; }

#endif
