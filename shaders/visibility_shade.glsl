// Visibility pass, shading (the body of visibility_shade_sh*.frag): one full-screen triangle per
// view. Each pixel reads the (instance, triangle) of its samples (visibility.frag), and for
// each distinct one fetches the triangle's three vertices, finds the perspective-correct
// barycentrics of the pixel centre (where the forward pass evaluates its varyings, MSAA or
// not) and of the centres one pixel right and one pixel down (the texture gradients and the
// normal's screen-space variance, which the forward pass takes from its 2x2 quad), and
// evaluates the material and its light exactly as forward_main.glsl does. The pixel's colour
// is the mean over its samples (a sample seeing nothing counts as the clear colour), written
// to every sample, so the resolve gives what the forward pass's samples resolve to.
//
// Not compiled on its own: visibility_shade_sh1..4.frag set PROBE_SH_ORDER, and the _ms
// variants VISIBILITY_MULTISAMPLED (the id image is then multisampled).
#extension GL_EXT_nonuniform_qualifier : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "raster_common.glsl"
#include "forward_variant.glsl"
#include "probe_lighting.glsl"
#include "surface_lighting.glsl"

// Specialization constants after forward_variant.glsl's 0..5 (raster/visibility_pass.cpp).
layout(constant_id = 10) const int kSlotImages = 5;      // five per material, default last
layout(constant_id = 11) const int kMaterialStride = 15; // vec4s from one material to the next
layout(constant_id = 12) const int kSamples = 1;

// Set 3 (raster::VisibilityPass): the ids, the instances, the scene's buffers, the materials.
#ifdef VISIBILITY_MULTISAMPLED
layout(set = 3, binding = 0) uniform usampler2DMSArray ids;
uvec2 id_at(ivec3 p, int s) { return texelFetch(ids, p, s).xy; }
vec2 id_size() { return vec2(textureSize(ids).xy); }
#else
layout(set = 3, binding = 0) uniform usampler2DArray ids;
uvec2 id_at(ivec3 p, int s) { return texelFetch(ids, p, 0).xy; }
vec2 id_size() { return vec2(textureSize(ids, 0).xy); }
#endif
struct Instance {
  mat4 model;
  vec4 normal_matrix[3];  // as DrawConstants: columns; [0].w the tangent handedness sign
  uvec4 info;             // x: material (MaterialTextures' set order), y: vertex offset, z: 1 = mirrored
};
layout(set = 3, binding = 1, std430) readonly buffer Instances { Instance instances[]; };
layout(set = 3, binding = 2, std430) readonly buffer Indices { uint indices[]; };
// raster::Vertex, 18 floats: position 0, normal 3, uv 6, tangent 8, uv1 12, colour 14.
layout(set = 3, binding = 3, std430) readonly buffer Vertices { float vertex_floats[]; };
layout(set = 3, binding = 4, std430) readonly buffer Materials { vec4 material_vec4[]; };
layout(set = 3, binding = 5) uniform sampler2D slot_textures[kSlotImages];

layout(location = 0) out vec4 out_color;

const uint kNothing = 0xffffffffu;     // the ids' clear value
const uint kBackFacing = 0x80000000u;  // in an id's x: the sample sees the triangle's back

vec2 vertex2(uint v, uint o) { return vec2(vertex_floats[18u * v + o], vertex_floats[18u * v + o + 1u]); }
vec3 vertex3(uint v, uint o) { return vec3(vertex2(v, o), vertex_floats[18u * v + o + 2u]); }
vec4 vertex4(uint v, uint o) { return vec4(vertex3(v, o), vertex_floats[18u * v + o + 3u]); }

// Perspective-correct barycentrics of the NDC point q in the triangle with clip positions c*.
vec3 barycentrics(vec2 q, vec4 c0, vec4 c1, vec4 c2) {
  const vec2 a = c0.xy / c0.w, b = c1.xy / c1.w, c = c2.xy / c2.w;
  const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  const float l1 = ((c.x - q.x) * (a.y - q.y) - (c.y - q.y) * (a.x - q.x)) / area;
  const float l2 = ((a.x - q.x) * (b.y - q.y) - (a.y - q.y) * (b.x - q.x)) / area;
  const vec3 l = vec3(1.0 - l1 - l2, l1, l2) / vec3(c0.w, c1.w, c2.w);
  return l / (l.x + l.y + l.z);
}

// One material, read from the uniform blocks' storage view (MaterialData's order).
struct Material {
  vec4 base_color, emission, params, alpha, dielectric;
  uint base;  // index of its first vec4
  int first_slot;
};

// Texture slot s at the pixel: its UV set and KHR_texture_transform (forward_material.glsl's
// slot_uv), sampled with the gradients of the transformed coordinate.
vec4 read_slot(Material m, int s, vec4 uv, vec4 uv_dx, vec4 uv_dy) {
  const vec4 r0 = material_vec4[m.base + 4u + uint(2 * s)];
  const vec4 r1 = material_vec4[m.base + 5u + uint(2 * s)];
  const bool second = r0.w > 0.5;
  const vec2 t = second ? uv.zw : uv.xy;
  const vec2 dx = second ? uv_dx.zw : uv_dx.xy;
  const vec2 dy = second ? uv_dy.zw : uv_dy.xy;
  const vec2 p = vec2(dot(r0.xyz, vec3(t, 1.0)), dot(r1.xyz, vec3(t, 1.0)));
  const vec2 gx = vec2(dot(r0.xy, dx), dot(r1.xy, dx));
  const vec2 gy = vec2(dot(r0.xy, dy), dot(r1.xy, dy));
  // One texture at a time for the lanes that share it (a 4x4 block mostly holds one
  // material): an index the same in every lane that reads takes lavapipe's one-call path,
  // where a non-uniform one is sampled lane by lane.
  const uint index = uint(m.first_slot + s);
  vec4 texel = vec4(0.0);
  for (;;) {
    const uint first = subgroupBroadcastFirst(index);
    if (first == index) {
      texel = textureGrad(slot_textures[first], p, gx, gy);
      break;
    }
  }
  return texel;
}

bool has_slot(Material m, uint bit) { return kTextures && (uint(m.alpha.z) & bit) != 0u; }

// The linear radiance of triangle `id` at the pixel centre q (NDC), seen from views[view].
vec3 shade(uvec2 id, uint view, vec2 q, vec2 pixel) {
  const Instance inst = instances[id.x & ~kBackFacing];
  const uint vo = inst.info.y;
  const uint i0 = indices[3u * id.y] + vo;
  const uint i1 = indices[3u * id.y + 1u] + vo;
  const uint i2 = indices[3u * id.y + 2u] + vo;
  const vec3 w0 = (inst.model * vec4(vertex3(i0, 0u), 1.0)).xyz;
  const vec3 w1 = (inst.model * vec4(vertex3(i1, 0u), 1.0)).xyz;
  const vec3 w2 = (inst.model * vec4(vertex3(i2, 0u), 1.0)).xyz;
  const mat4 vp = views[view].view_proj;
  const vec4 c0 = vp * vec4(w0, 1.0), c1 = vp * vec4(w1, 1.0), c2 = vp * vec4(w2, 1.0);
  const vec3 l = barycentrics(q, c0, c1, c2);
  const vec3 lx = barycentrics(q + vec2(pixel.x, 0.0), c0, c1, c2);
  const vec3 ly = barycentrics(q + vec2(0.0, pixel.y), c0, c1, c2);
  const vec3 world = l.x * w0 + l.y * w1 + l.z * w2;

  const mat3 nm = mat3(inst.normal_matrix[0].xyz, inst.normal_matrix[1].xyz, inst.normal_matrix[2].xyz);
  const vec3 n0 = nm * vertex3(i0, 3u), n1 = nm * vertex3(i1, 3u), n2 = nm * vertex3(i2, 3u);
  const vec3 normal = normalize(l.x * n0 + l.y * n1 + l.z * n2);
  const vec3 dndx = normalize(lx.x * n0 + lx.y * n1 + lx.z * n2) - normal;
  const vec3 dndy = normalize(ly.x * n0 + ly.y * n1 + ly.z * n2) - normal;
  const float normal_variance = 0.15915494 * (dot(dndx, dndx) + dot(dndy, dndy));

  Material m;
  m.base = inst.info.x * uint(kMaterialStride);
  m.base_color = material_vec4[m.base];
  m.emission = material_vec4[m.base + 1u];
  m.params = material_vec4[m.base + 2u];
  m.alpha = material_vec4[m.base + 3u];
  m.dielectric = material_vec4[m.base + 14u];
  m.first_slot = int(inst.info.x) * 5;

  vec4 uv = vec4(0.0), uv_dx = vec4(0.0), uv_dy = vec4(0.0);
  if (kTextures && uint(m.alpha.z) != 0u) {
    const vec4 u0 = vec4(vertex2(i0, 6u), vertex2(i0, 12u));
    const vec4 u1 = vec4(vertex2(i1, 6u), vertex2(i1, 12u));
    const vec4 u2 = vec4(vertex2(i2, 6u), vertex2(i2, 12u));
    uv = l.x * u0 + l.y * u1 + l.z * u2;
    uv_dx = lx.x * u0 + lx.y * u1 + lx.z * u2 - uv;
    uv_dy = ly.x * u0 + ly.y * u1 + ly.z * u2 - uv;
  }
  vec4 base = m.base_color * (l.x * vertex4(i0, 14u) + l.y * vertex4(i1, 14u) + l.z * vertex4(i2, 14u));
  if (has_slot(m, 1u)) base *= read_slot(m, 0, uv, uv_dx, uv_dy);
  float metallic = m.params.x;
  float roughness = m.params.y;
  if (has_slot(m, 2u)) {
    const vec4 mr = read_slot(m, 1, uv, uv_dx, uv_dy);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  const vec3 albedo = clamp(base.rgb, 0.0, 1.0);
  if (m.emission.w > 0.5) return albedo;  // KHR_materials_unlit

  // The rasterizer's facing: glTF's counter-clockwise front faces, clockwise under a mirroring
  // transform (forward_pass.cpp's front face), seen from the view's eye.
  const bool front = (dot(cross(w1 - w0, w2 - w0), views[view].eye.xyz - w0) > 0.0) != (inst.info.z != 0u);
  vec3 n = front ? normal : -normal;
  if (has_slot(m, 4u)) {
    const vec4 tangent = l.x * vertex4(i0, 8u) + l.y * vertex4(i1, 8u) + l.z * vertex4(i2, 8u);
    vec3 t = mat3(inst.model) * tangent.xyz;
    t -= n * dot(n, t);
    if (dot(t, t) > 1e-20) {
      t = normalize(t);
      const float handedness = tangent.w * inst.normal_matrix[0].w;
      const vec3 b = cross(n, t) * (handedness < 0.0 ? -1.0 : 1.0) * (front ? 1.0 : -1.0);
      const vec3 c = read_slot(m, 2, uv, uv_dx, uv_dy).xyz * 2.0 - 1.0;
      n = normalize(t * c.x * m.params.z + b * c.y * m.params.z + n * c.z);
    }
  }
  float occlusion = 1.0;
  if (kProbes && has_slot(m, 8u))
    occlusion = 1.0 + m.params.w * (read_slot(m, 3, uv, uv_dx, uv_dy).r - 1.0);
  vec3 color = vec3(0.0);
  if (kEmission && front) {
    color = m.emission.rgb;
    if (has_slot(m, 16u)) color *= read_slot(m, 4, uv, uv_dx, uv_dy).rgb;
  }
  return color + lighting(world, view, m.dielectric, n, albedo, metallic, roughness,
                          normal_variance, occlusion);
}

// Whether triangle b continues triangle a's surface, so that the samples b covers can take a's
// shading at the pixel centre (which extrapolates a's attributes there, as the forward pass
// does for every triangle at an MSAA pixel's centre): the same instance seen from the same side
// (so the same material, transform and facing: the ids' x, kBackFacing included) and a vertex
// in common (an indexed mesh shares a vertex only where its normal, UVs, tangent and colour are
// continuous: glTF's creases and seams duplicate vertices). Most of a finely tessellated
// scene's edge pixels are such inner edges; shading each of their triangles cost almost as
// much again as the first (raster/visibility_pass.h). The test reads six indices, no vertex.
bool continues(uvec2 a, uvec2 b) {
  if (a.x != b.x) return false;
  const uint a0 = indices[3u * a.y], a1 = indices[3u * a.y + 1u], a2 = indices[3u * a.y + 2u];
  const uint b0 = indices[3u * b.y], b1 = indices[3u * b.y + 1u], b2 = indices[3u * b.y + 2u];
  return b0 == a0 || b0 == a1 || b0 == a2 || b1 == a0 || b1 == a1 || b1 == a2 || b2 == a0 ||
         b2 == a1 || b2 == a2;
}

void main() {
  const uint view = pc.view_index;
  const ivec3 p = ivec3(ivec2(gl_FragCoord.xy), int(view));
  // The pixel's distinct surfaces and how many samples each covers (a triangle that continues
  // an earlier one's surface joins it); the first is shaded for every pixel, the others where
  // the pixel has them (silhouettes, creases, seams, material edges). On lavapipe a
  // block of pixels shades a second time when any of its pixels needs it: with Sponza's
  // pixel-sized triangles that is most blocks at MSAA 4 (raster/visibility_pass.h).
  uvec2 triangle[kSamples];
  float covered[kSamples];
  int distinct = 0;
  float nothing = 0.0;  // samples that see no geometry
  for (int s = 0; s < kSamples; ++s) {
    const uvec2 id = id_at(p, s);
    if (id.x == kNothing) {
      nothing += 1.0;
      continue;
    }
    bool known = false;
    for (int k = 0; k < distinct && !known; ++k)
      if (triangle[k] == id || continues(triangle[k], id)) {
        covered[k] += 1.0;
        known = true;
      }
    if (!known) {
      triangle[distinct] = id;
      covered[distinct] = 1.0;
      ++distinct;
    }
  }
  if (distinct == 0) discard;  // the clear colour is there already
  const vec2 size = id_size();
  const vec2 q = gl_FragCoord.xy / size * 2.0 - 1.0;
  const vec2 pixel = 2.0 / size;
  const vec4 clear_color = pc.model[0];  // raster::VisibilityPass: the pass's clear colour
  vec4 sum = nothing * clear_color + covered[0] * vec4(shade(triangle[0], view, q, pixel), 1.0);
  for (int k = 1; k < distinct; ++k) sum += covered[k] * vec4(shade(triangle[k], view, q, pixel), 1.0);
  out_color = sum / float(kSamples);
}
