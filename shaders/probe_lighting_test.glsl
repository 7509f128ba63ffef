// Body of the test harness for probe_lighting.glsl (tests/raster/probe_lighting_test.cpp): it
// evaluates one query per invocation and writes the result, so the host can compare every GLSL
// function with the CPU sh, trace and raster modules. Compiled at orders 1 to 4 by
// probe_lighting_test_l{1,2,3,4}.comp, which set PROBE_SH_ORDER and include this file.
#ifndef DDISH_PROBE_LIGHTING_TEST_GLSL
#define DDISH_PROBE_LIGHTING_TEST_GLSL
#include "probe_lighting.glsl"

layout(local_size_x = 64) in;

// query.a: xyz world position (or x = n.v for the table lookups), w = roughness;
// query.b: xyz normal or reflected direction, w = what to evaluate (kind below).
struct Query {
  vec4 a;
  vec4 b;
};
layout(std430, set = 0, binding = 0) readonly buffer Queries { Query queries[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { vec4 results[]; };

layout(push_constant) uniform Params { uint count; } params;

const uint kIrradiance = 0u;
const uint kSpecular = 1u;
const uint kDfg = 2u;
const uint kGgxZh = 3u;
const uint kInterpolatedL0 = 4u;  // the interpolated band-0 coefficient and the weight flag
const uint kLightingIrradiance = 5u;  // probe_lighting's two outputs
const uint kLightingSpecular = 6u;
const uint kVisibleL0 = 7u;  // as kInterpolatedL0, with normal b.xyz and the viewer along it

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  const Query q = queries[i];
  const uint kind = uint(q.b.w);
  vec4 r = vec4(0.0);
  if (kind == kIrradiance) {
    r.xyz = probe_irradiance(q.a.xyz, q.b.xyz);
  } else if (kind == kSpecular) {
    r.xyz = probe_specular(q.a.xyz, q.b.xyz, q.a.w);
  } else if (kind == kDfg) {
    r.xy = brdf_dfg(q.a.x, q.a.w);
  } else if (kind == kGgxZh) {
    r = brdf_ggx_zh(q.a.w);
  } else if (kind == kInterpolatedL0) {
    vec3 sh[PROBE_SH_COEFFS];
    r.w = probe_interpolate(q.a.xyz, vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0), sh) ? 1.0 : 0.0;
    r.xyz = sh[0];
  } else if (kind == kVisibleL0) {
    vec3 sh[PROBE_SH_COEFFS];
    r.w = probe_interpolate(q.a.xyz, q.b.xyz, q.b.xyz, sh) ? 1.0 : 0.0;
    r.xyz = sh[0];
  } else if (kind == kLightingIrradiance || kind == kLightingSpecular) {
    // a.xyz position, b.xyz reflected direction, normal = the reflected direction mirrored in z.
    const vec3 n = normalize(vec3(q.b.xy, -q.b.z) + vec3(0.1, 0.2, 0.3));
    vec3 irradiance, specular;
    probe_lighting(q.a.xyz, n, q.b.xyz, q.a.w, irradiance, specular);
    r.xyz = kind == kLightingIrradiance ? irradiance : specular;
  }
  results[i] = r;
}

#endif  // DDISH_PROBE_LIGHTING_TEST_GLSL
