// Forward pass, fragment stage (the body of forward_sh*.frag): the glTF metallic-roughness BSDF exactly as the path tracer
// evaluates it (src/trace/bsdf.cpp): GGX with alpha = roughness^2 (floored at 1e-3), the
// height-correlated Smith visibility, Schlick Fresnel with F0 = mix(F0d, base, metallic) (F0d
// 0.04 unless KHR_materials_ior / KHR_materials_specular change it, with the layer's weight),
// and the diffuse base scaled by (1 - E(n.v)) (1 - E(n.l)) / (1 - E_avg), E being the albedo of
// the dielectric layer (from trace::DielectricSpecularAlbedo's tables, interpolated the same
// way). Vertex colours multiply the base colour; each texture slot reads its UV set through its
// KHR_texture_transform; BLEND materials write their alpha for the transparent pass. Direct light comes from punctual lights with shadow maps; indirect light from
// the SH probes (probe_lighting.glsl), both evaluated by include/surface_lighting.glsl; emission
// is added; the environment is the clear colour.
//
// Not compiled on its own: forward_sh1..4.frag set PROBE_SH_ORDER (a compile-time constant of
// probe_lighting.glsl) and include this, one SPIR-V per SH order; forward_sh1..4_prepassed.frag
// also set FORWARD_AFTER_PREPASS, for the shading pass after a depth prepass.
#include "raster_common.glsl"
#include "forward_material.glsl"
#include "probe_lighting.glsl"

#ifdef FORWARD_AFTER_PREPASS
// After the depth prepass (raster/forward_pass.h) the depth test (less or equal, no writes) runs
// before the shader, and with post-depth coverage gl_SampleMaskIn holds the samples that passed
// it: a fragment with none is hidden, and its lighting is skipped. That is what makes the
// prepass pay on lavapipe, whose multisampled path runs the fragment shader of every covered
// fragment after the early depth test (its single-sample path skips only groups of 8 failed
// pixels), but which skips an if whose condition is false in all 8 lanes of a pixel group.
layout(early_fragment_tests) in;
layout(post_depth_coverage) in;
#endif

#include "surface_lighting.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) flat in uint in_view;  // which views[] entry (forward_vertex.glsl)

layout(location = 0) out vec4 out_color;

void main() {
  const vec3 dndx = dFdx(normalize(in_normal));
  const vec3 dndy = dFdy(normalize(in_normal));
  const float normal_variance = 0.15915494 * (dot(dndx, dndx) + dot(dndy, dndy));
  vec4 base = material_base_color();
  if (masked_out(base.a)) discard;

  float metallic = material.params.x;
  float roughness = material.params.y;
  if (has_texture(2u)) {
    const vec4 mr = texture(metallic_roughness_tex, slot_uv(1));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  const vec3 albedo = clamp(base.rgb, 0.0, 1.0);
  // KHR_materials_unlit: the base colour, no light, as the path tracer shows it
  // (trace/surface.cpp); single-sided back faces are culled before they get here.
  // BLEND (the transparent pass, raster/forward_pass.h) writes the base colour's alpha for the
  // blend unit; every other mode covers what is behind.
  const float coverage = material.alpha.w > 0.5 ? clamp(base.a, 0.0, 1.0) : 1.0;
  if (material.emission.w > 0.5) {
    out_color = vec4(albedo, coverage);
    return;
  }

  // Shading normal: double-sided surfaces seen from behind turn to the viewer (single-sided
  // back faces are culled, as the tracer ends paths there).
  vec3 n = normalize(in_normal);
  if (!gl_FrontFacing) n = -n;
  if (has_texture(4u)) {
    vec3 t = in_tangent.xyz - n * dot(n, in_tangent.xyz);
    if (dot(t, t) > 1e-20) {
      t = normalize(t);
      const vec3 b = cross(n, t) * (in_tangent.w < 0.0 ? -1.0 : 1.0) * (gl_FrontFacing ? 1.0 : -1.0);
      const vec3 c = texture(normal_tex, slot_uv(2)).xyz * 2.0 - 1.0;
      n = normalize(t * c.x * material.params.z + b * c.y * material.params.z + n * c.z);
    }
  }
  float occlusion = 1.0;
  if (kProbes && has_texture(8u))
    occlusion = 1.0 + material.params.w * (texture(occlusion_tex, slot_uv(3)).r - 1.0);
  vec3 color = vec3(0.0);
  if (kEmission && gl_FrontFacing) {
    color = material.emission.rgb;
    if (has_texture(16u)) color *= texture(emissive_tex, slot_uv(4)).rgb;
  }
#ifdef FORWARD_AFTER_PREPASS
  if (gl_SampleMaskIn[0] != 0)  // some sample passed the depth test (see the top)
#endif
    color += lighting(in_world, in_view, material.dielectric, n, albedo, metallic, roughness,
                      normal_variance, occlusion);
  out_color = vec4(color, coverage);
}
