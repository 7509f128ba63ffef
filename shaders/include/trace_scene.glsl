// The GPU probe tracer's scene (src/trace_vk/scene_buffers.h writes these buffers; the structs
// must match its C++ structs, std430): meshes in object space with their triangles in the
// spatially sorted order the acceleration structures were built from, instances, materials,
// the emissive triangles with their power CDF, punctual lights and the BSDF's albedo table.
#ifndef DDISH_TRACE_SCENE_GLSL
#define DDISH_TRACE_SCENE_GLSL

#extension GL_EXT_ray_tracing : require

struct TraceVertex {
  vec4 position_u;  // object-space position, UV0.x
  vec4 normal_v;    // object-space normal (zero: none), UV0.y
  vec4 tangent;     // glTF tangent, w handedness (zero: none)
  vec4 color;       // COLOR_0 (white: none)
  vec4 uv1;         // TEXCOORD_1 in xy
};

struct TraceMesh {
  uint first_index;   // into indices (3 per triangle)
  uint first_vertex;  // added to every index
  uint triangle_count;
  uint material;
};

struct TraceInstance {
  mat4 object_to_world;
  mat4 normal_matrix;   // inverse transpose of the upper 3x3 (in a mat4)
  uint mesh;
  int emissive_first;   // this instance's first triangle in the emissive list, or -1
  uint mirrored;        // negative determinant: clockwise triangles face front
  uint pad;
};

const uint MATERIAL_DOUBLE_SIDED = 1u;
const uint MATERIAL_UNLIT = 2u;
const uint MATERIAL_MASK = 4u;
const uint MATERIAL_BLEND = 8u;

struct TextureSlot {
  int texture;     // -1: none
  uint texcoord;   // UV set 0 or 1
  uint sampler_bits;    // wrap s | wrap t << 2 | mag << 4 | min << 5 | mip << 6
  float area_scale;
  vec4 row0;       // KHR_texture_transform: u' = dot(row0.xyz, (u, v, 1))
  vec4 row1;
};

struct TraceMaterial {
  vec4 base_color;
  vec4 emission_metallic;       // emission (factor x strength), metallic
  vec4 dielectric_f0_roughness; // the dielectric layer's F0, roughness
  float specular;
  uint flags;
  float alpha_cutoff;
  float normal_scale;
  TextureSlot base_color_texture;
  TextureSlot metallic_roughness_texture;
  TextureSlot normal_texture;
  TextureSlot emissive_texture;
};

struct TraceTexture {
  uint first_level;
  uint levels;
  float half_log2_texels;
  uint pad;
};

struct TraceTextureLevel {
  uint offset;
  uint width;
  uint height;
  uint pad;
};

struct EmissiveTriangle {
  vec4 p0_area;
  vec4 e1_magnitude;
  vec4 e2_double_sided;  // w: 1 when double sided
  vec4 normal_cdf;       // unit front normal; w: the CDF up to and including this triangle
  vec4 radiance_prob;    // emitted radiance; w: the probability of picking this triangle
  uint instance;         // the instance and primitive (for the emissive texture)
  uint prim;
  uint pad0, pad1;
};

const uint LIGHT_DIRECTIONAL = 0u;
const uint LIGHT_POINT = 1u;
const uint LIGHT_SPOT = 2u;

struct TraceLight {
  vec4 position_type;     // w: LIGHT_*
  vec4 direction_range;   // where the light travels (unit), range (0: none)
  vec4 radiant;           // colour x intensity
  vec4 spot;              // x: scale, y: offset of glTF's spot falloff
};

#ifndef TRACE_SCENE_NO_TLAS
layout(set = 0, binding = 0) uniform accelerationStructureEXT scene_tlas;
#endif
layout(std430, set = 0, binding = 3) readonly buffer Vertices { TraceVertex vertices[]; };
layout(std430, set = 0, binding = 4) readonly buffer Indices { uint indices[]; };
layout(std430, set = 0, binding = 5) readonly buffer Meshes { TraceMesh meshes[]; };
layout(std430, set = 0, binding = 6) readonly buffer Instances { TraceInstance instances[]; };
layout(std430, set = 0, binding = 7) readonly buffer Materials { TraceMaterial materials[]; };
layout(std430, set = 0, binding = 8) readonly buffer Emissive { EmissiveTriangle emissive[]; };
layout(std430, set = 0, binding = 9) readonly buffer Lights { TraceLight lights[]; };
layout(std430, set = 0, binding = 10) readonly buffer AlbedoTable {
  float albedo_e[ALBEDO_TABLE_SIZE];
  float albedo_s[ALBEDO_TABLE_SIZE];
  float albedo_e_avg[32];
  float albedo_s_avg[32];
};
layout(std430, set = 0, binding = 12) readonly buffer Textures { TraceTexture textures[]; };
layout(std430, set = 0, binding = 13) readonly buffer TextureLevels { TraceTextureLevel texture_levels[]; };
layout(std430, set = 0, binding = 14) readonly buffer Texels { uint texels[]; };

#endif  // DDISH_TRACE_SCENE_GLSL
