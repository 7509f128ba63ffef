// Texture lookups of the GPU probe tracer, as trace::MipTexture does them on the CPU (read
// src/trace/texture_lookup.cpp; this must follow it): RGBA8 mip chains in a storage buffer,
// the glTF sampler_bits's addressing (repeat, clamp, mirrored repeat) and filters (nearest / linear
// within a level, none / nearest / linear between levels), sRGB decoded per texel before
// filtering, and the ray-cone footprint's mip level. Needs trace_scene.glsl.
#ifndef DDISH_TRACE_TEXTURE_GLSL
#define DDISH_TRACE_TEXTURE_GLSL

const uint WRAP_REPEAT = 0u;
const uint WRAP_CLAMP = 1u;
const uint WRAP_MIRROR = 2u;
const uint FILTER_NEAREST = 0u;
const uint MIP_NONE = 0u;
const uint MIP_NEAREST = 1u;

int tex_address(int i, int n, uint mode) {
  if (mode == WRAP_CLAMP) return clamp(i, 0, n - 1);
  if (mode == WRAP_MIRROR) {
    int m = i % (2 * n);
    if (m < 0) m += 2 * n;
    return m < n ? m : 2 * n - 1 - m;
  }
  const int m = i % n;
  return m < 0 ? m + n : m;
}

float tex_reduce(float x, uint mode) {
  if (isnan(x) || isinf(x)) return 0.0;
  if (mode == WRAP_CLAMP) return clamp(x, -1.0, 2.0);
  if (mode == WRAP_MIRROR) return x - 2.0 * floor(0.5 * x);
  return x - floor(x);
}

float srgb_decode(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

vec4 tex_decode(uint packed, bool srgb) {
  const vec4 c = vec4(float(packed & 0xFFu), float((packed >> 8) & 0xFFu), float((packed >> 16) & 0xFFu),
                      float(packed >> 24)) * (1.0 / 255.0);
  if (srgb) return vec4(srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b), c.a);
  return c;
}

vec4 tex_texel(TraceTextureLevel l, int x, int y, bool srgb, uint sampler_bits) {
  const int w = int(l.width), h = int(l.height);
  const int xi = tex_address(x, w, sampler_bits & 3u);
  const int yi = tex_address(y, h, (sampler_bits >> 2) & 3u);
  return tex_decode(texels[l.offset + uint(yi * w + xi)], srgb);
}

vec4 tex_sample_level(TraceTexture t, vec2 uv, uint level, bool srgb, uint sampler_bits, uint filter_mode) {
  const TraceTextureLevel l = texture_levels[t.first_level + level];
  uv = vec2(tex_reduce(uv.x, sampler_bits & 3u), tex_reduce(uv.y, (sampler_bits >> 2) & 3u));
  // Nearest: the texel whose square holds uv, once. Linear: texel centres at half-integers, the
  // four around uv. One texel fetch in a loop keeps the shader small (CPU drivers inline all).
  const bool nearest = filter_mode == FILTER_NEAREST;
  const vec2 f = nearest ? uv * vec2(l.width, l.height) : uv * vec2(l.width, l.height) - 0.5;
  const vec2 f0 = floor(f);
  const vec2 frac = nearest ? vec2(0.0) : f - f0;
  const ivec2 i0 = ivec2(f0);
  vec4 corners[4];
  const int count = nearest ? 1 : 4;
  for (int k = 0; k < count; ++k) corners[k] = tex_texel(l, i0.x + (k & 1), i0.y + (k >> 1), srgb, sampler_bits);
  if (nearest) return corners[0];
  return mix(mix(corners[0], corners[1], frac.x), mix(corners[2], corners[3], frac.x), frac.y);
}

// trace::MipTexture::sample: the level(s) and filter first, then one lookup per level.
vec4 tex_sample(int index, vec2 uv, float lod, bool srgb, uint sampler_bits) {
  const TraceTexture t = textures[index];
  const float max_level = float(t.levels - 1u);
  lod = (isnan(lod) || isinf(lod)) ? 0.0 : clamp(lod, 0.0, max_level);
  const uint mag = (sampler_bits >> 4) & 1u, min_filter = (sampler_bits >> 5) & 1u, mip = (sampler_bits >> 6) & 3u;
  uint level = 0u;
  uint filter_mode = min_filter;
  float blend = 0.0;  // > 0: also the next level, by this much
  if (lod <= 0.0) {
    filter_mode = mag;
  } else if (mip == MIP_NEAREST) {
    level = uint(floor(lod + 0.5));
  } else if (mip != MIP_NONE) {
    level = uint(lod);
    blend = level + 1u < t.levels ? lod - float(level) : 0.0;
  }
  vec4 result = vec4(0.0);
  const int count = blend > 0.0 ? 2 : 1;
  for (int k = 0; k < count; ++k)
    result += tex_sample_level(t, uv, level + uint(k), srgb, sampler_bits, filter_mode) *
              (k == 0 ? 1.0 - blend : blend);
  return result;
}

// log2 of a ray-cone footprint in UV units (MipTexture::footprint_log2): -inf without one.
float footprint_log2(float width, float cos_theta, float uv_area, float world_area) {
  if (!(width > 0.0) || !(uv_area > 0.0) || !(world_area > 0.0)) return -3.402823466e38 * 2.0;
  return log2(width * sqrt(uv_area / world_area) / max(abs(cos_theta), 0.05));
}

float texture_lod(int index, float log2_footprint) {
  return max(0.0, log2_footprint + textures[index].half_log2_texels);
}

// The three vertices of a triangle and its slot UVs (after the transform) at weights w.
struct TriangleVertices {
  TraceVertex v0, v1, v2;
};

TriangleVertices triangle_vertices(uint instance_index, uint prim) {
  const TraceMesh mesh = meshes[instances[instance_index].mesh];
  TriangleVertices t;
  t.v0 = vertices[indices[mesh.first_index + 3u * prim] + mesh.first_vertex];
  t.v1 = vertices[indices[mesh.first_index + 3u * prim + 1u] + mesh.first_vertex];
  t.v2 = vertices[indices[mesh.first_index + 3u * prim + 2u] + mesh.first_vertex];
  return t;
}

vec2 vertex_uv(TraceVertex v, uint set) { return set == 1u ? v.uv1.xy : vec2(v.position_u.w, v.normal_v.w); }

vec2 slot_uv(TextureSlot slot, TriangleVertices t, vec3 w) {
  const vec2 uv = vertex_uv(t.v0, slot.texcoord) * w.x + vertex_uv(t.v1, slot.texcoord) * w.y +
                  vertex_uv(t.v2, slot.texcoord) * w.z;
  const vec3 h = vec3(uv, 1.0);
  return vec2(dot(slot.row0.xyz, h), dot(slot.row1.xyz, h));
}

float slot_uv_area(TextureSlot slot, TriangleVertices t) {
  const vec2 a = vertex_uv(t.v1, slot.texcoord) - vertex_uv(t.v0, slot.texcoord);
  const vec2 b = vertex_uv(t.v2, slot.texcoord) - vertex_uv(t.v0, slot.texcoord);
  return 0.5 * abs(a.x * b.y - a.y * b.x) * slot.area_scale;
}

// A slot's lookup at a hit: uv, mip level from the footprint.
vec4 slot_sample(TextureSlot slot, TriangleVertices t, vec3 w, float width, float cos_theta, float world_area,
                 bool srgb) {
  const float lod = texture_lod(slot.texture, footprint_log2(width, cos_theta, slot_uv_area(slot, t), world_area));
  return tex_sample(slot.texture, slot_uv(slot, t, w), lod, srgb, slot.sampler_bits);
}

#endif  // DDISH_TRACE_TEXTURE_GLSL
