// Declarations shared by the rasterizer's stages (forward.vert, forward.frag, shadow.vert):
// the per-draw push constants and the frame data of descriptor set 0. The C++ mirrors are in
// src/raster/gpu_types.h; std430/std140 layouts are chosen so both sides agree byte for byte.
#ifndef DDISH_RASTER_COMMON_GLSL
#define DDISH_RASTER_COMMON_GLSL

#extension GL_GOOGLE_include_directive : enable

// Per draw: the instance's object-to-world transform, its normal matrix (columns xyz; w of
// column 0 is the tangent handedness sign, -1 for mirroring transforms), which view or
// shadow-map layer the draw is for, and what the visibility pass writes per sample.
layout(push_constant) uniform DrawConstants {
  mat4 model;
  vec4 normal_matrix[3];
  uint view_index;   // forward: the pass's first view in views[]; shadow: shadow_layers[] index
  uint material;     // unused by the shaders, kept for debugging captures
  uint instance;        // the visibility pass: the scene instance drawn
  uint first_triangle;  // the visibility pass: the draw's first triangle in the index buffer
} pc;

struct ViewData {
  mat4 view_proj;
  vec4 eye;  // xyz: camera position
};

// Set 0: what every draw of a frame shares.
layout(set = 0, binding = 0) uniform FrameData {
  vec4 environment;    // rgb: uniform environment radiance
  uvec4 counts;        // x: punctual lights, y: shadow layers, z: views
  vec4 shadow_params;  // x: 1 / shadow map size, y: PCF radius in texels, z: 1 = bilinear compares
} frame;

layout(set = 0, binding = 1, std430) readonly buffer Views { ViewData views[]; };

#endif

// Light types, as LightData.direction_type.w holds them.
const uint kLightDirectional = 0u;
const uint kLightPoint = 1u;
const uint kLightSpot = 2u;

struct LightData {
  vec4 position_range;  // xyz: position; w: glTF range (0 = infinite)
  vec4 direction_type;  // xyz: unit direction the light travels; w: type
  vec4 radiant;         // rgb: colour × intensity (radiometric, as the tracer's)
  vec4 spot_shadow;     // x, y: spot cone scale, offset; z: first shadow layer (-1: none); w: layers
};

struct ShadowLayer {
  mat4 light_view_proj;  // world -> the layer's clip space (Vulkan depth 0..1)
  vec4 params;           // x: depth bias; y: normal offset (world units, per unit distance when z = 1)
};

layout(set = 0, binding = 2, std430) readonly buffer Lights { LightData lights[]; };
layout(set = 0, binding = 3, std430) readonly buffer ShadowLayers { ShadowLayer shadow_layers[]; };
