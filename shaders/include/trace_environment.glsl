// The GPU probe tracer's environment map (src/trace_vk/scene_layout.h writes the buffers): an
// equirectangular map with scene/environment_map.cpp's conventions (row 0 at +Y, the centre
// column at -Z, u toward +X, the rotation about +Y, bilinear between texel centres, wrapping in
// u and clamped in v), sampled as trace::EnvironmentLight samples it (its own tables: a row by
// the row CDF, a column by the row's column CDF, the point uniform within the texel; density
// p(u, v) / (2 pi^2 sin theta)). Needs PI (trace_bsdf.glsl).
#ifndef DDISH_TRACE_ENVIRONMENT_GLSL
#define DDISH_TRACE_ENVIRONMENT_GLSL

struct EnvironmentParams {
  uint width;  // 0: no map
  uint height;
  float cos_rotation;
  float sin_rotation;
};

// Radiance in rgb; w: the texel's density in (u, v).
layout(std430, set = 0, binding = 15) readonly buffer EnvironmentTexels { vec4 environment_texels[]; };
// The row CDF (height + 1 entries), then each row's column CDF (width + 1 entries each).
layout(std430, set = 0, binding = 16) readonly buffer EnvironmentCdf { float environment_cdf[]; };

// EnvironmentMap::uv_of: the file's direction is the world direction turned back by the rotation.
vec2 environment_uv(EnvironmentParams e, vec3 d) {
  const float x = e.cos_rotation * d.x - e.sin_rotation * d.z;
  const float z = e.sin_rotation * d.x + e.cos_rotation * d.z;
  // atan(0, 0) is undefined in GLSL; at a pole every u names the same direction.
  float u = 0.5 + (x == 0.0 && z == 0.0 ? 0.0 : atan(x, -z)) / (2.0 * PI);
  u = clamp(u, 0.0, 1.0);
  return vec2(u, acos(clamp(d.y, -1.0, 1.0)) / PI);
}

// EnvironmentMap::direction_of.
vec3 environment_direction(EnvironmentParams e, vec2 uv) {
  const float theta = uv.y * PI;
  const float phi = (uv.x - 0.5) * 2.0 * PI;
  const float st = sin(theta);
  const float xf = st * sin(phi);
  const float zf = -st * cos(phi);
  return vec3(e.cos_rotation * xf + e.sin_rotation * zf, cos(theta), -e.sin_rotation * xf + e.cos_rotation * zf);
}

// EnvironmentMap::radiance: bilinear between texel centres.
vec3 environment_radiance(EnvironmentParams e, vec3 d) {
  const vec2 uv = environment_uv(e, d);
  const int w = int(e.width), h = int(e.height);
  const float fx = uv.x * float(w) - 0.5;
  const float fy = clamp(uv.y * float(h) - 0.5, 0.0, float(h - 1));
  const float x0f = floor(fx), y0f = floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  int x0 = int(x0f);  // in [-1, w - 1]: wrap around
  if (x0 < 0) x0 += w;
  if (x0 >= w) x0 -= w;
  const int x1 = x0 + 1 == w ? 0 : x0 + 1;
  const int y0 = int(y0f);
  const int y1 = min(y0 + 1, h - 1);
  const vec3 top = mix(environment_texels[y0 * w + x0].rgb, environment_texels[y0 * w + x1].rgb, tx);
  const vec3 bottom = mix(environment_texels[y1 * w + x0].rgb, environment_texels[y1 * w + x1].rgb, tx);
  return mix(top, bottom, ty);
}

// environment_light.cpp's pick: the bin i of the n bins of the CDF at `first` with
// cdf[i] <= u < cdf[i + 1], skipping empty bins at the top, and u's fraction within it.
int environment_pick(uint first, int n, float u, out float fraction) {
  int lo = 0, hi = n + 1;  // the first entry greater than u (upper bound) lies in [lo, hi]
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (environment_cdf[first + uint(mid)] > u) hi = mid; else lo = mid + 1;
  }
  int i = clamp(lo - 1, 0, n - 1);
  while (i > 0 && environment_cdf[first + uint(i + 1)] <= environment_cdf[first + uint(i)]) --i;
  const float c0 = environment_cdf[first + uint(i)];
  const float width = environment_cdf[first + uint(i + 1)] - c0;
  fraction = width > 0.0 ? clamp((u - c0) / width, 0.0, 1.0) : 0.5;
  return i;
}

// EnvironmentLight::sample: false when u lands on a pole or an empty texel.
bool environment_sample(EnvironmentParams e, vec2 u, out vec3 wi, out vec3 radiance, out float pdf) {
  wi = vec3(0.0); radiance = vec3(0.0); pdf = 0.0;
  const int w = int(e.width), h = int(e.height);
  float fy, fx;
  const int y = environment_pick(0u, h, u.y, fy);
  const int x = environment_pick(uint(h + 1 + y * (w + 1)), w, u.x, fx);
  const vec2 uv = vec2((float(x) + fx) / float(w), (float(y) + fy) / float(h));
  const float sin_theta = sin(uv.y * PI);
  if (!(sin_theta > 0.0)) return false;
  const float p_uv = environment_texels[y * w + x].w;
  if (!(p_uv > 0.0)) return false;
  wi = environment_direction(e, uv);
  pdf = p_uv / (2.0 * PI * PI * sin_theta);
  radiance = environment_radiance(e, wi);
  return true;
}

// EnvironmentLight::pdf: the density with which environment_sample returns wi, per solid angle.
float environment_pdf(EnvironmentParams e, vec3 wi) {
  const vec2 uv = environment_uv(e, wi);
  const int w = int(e.width), h = int(e.height);
  const int x = clamp(int(uv.x * float(w)), 0, w - 1);
  const int y = clamp(int(uv.y * float(h)), 0, h - 1);
  const float sin_theta = sqrt(max(0.0, 1.0 - wi.y * wi.y));
  if (!(sin_theta > 0.0)) return 0.0;
  return environment_texels[y * w + x].w / (2.0 * PI * PI * sin_theta);
}

#endif  // DDISH_TRACE_ENVIRONMENT_GLSL
