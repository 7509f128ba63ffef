// Display encoding of the rasterizer's HDR output: reads the resolved RGBA16F pixels (copied to
// a buffer for readback anyway) and writes RGBA8 sRGB-encoded display values.
//   curve 0 (linear): clamp to [0, 1], then sRGB: exactly what metrics::write_png does with the
//     linear image, for images compared against references.
//   curve 1 (filmic): Narkowicz's fit of the ACES reference rendering transform,
//     f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), applied per channel to the
//     exposure-scaled value, then sRGB: highlights roll off instead of clipping.
#version 460

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Hdr { uvec2 hdr[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Display { uint display[]; };

layout(push_constant) uniform Params {
  uint pixels;
  uint curve;
  float exposure;
} params;

vec3 srgb_encode(vec3 c) {
  const vec3 lo = c * 12.92;
  const vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}

vec3 aces_fitted(vec3 x) {
  return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= params.pixels) return;
  const vec2 rg = unpackHalf2x16(hdr[i].x);
  const vec2 ba = unpackHalf2x16(hdr[i].y);
  vec3 c = max(vec3(rg, ba.x), vec3(0.0)) * params.exposure;
  c = params.curve == 1u ? aces_fitted(c) : clamp(c, 0.0, 1.0);
  // NaN fails every comparison: show it as black, not as whatever the bits round to.
  c = mix(vec3(0.0), c, equal(c, c));
  display[i] = packUnorm4x8(vec4(srgb_encode(c), 1.0));
}
