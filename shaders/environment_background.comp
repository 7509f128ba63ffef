// The environment map behind what the forward pass drew (raster/environment_background.h):
// pixel' = pixel + (1 - alpha) * L(direction of the pixel centre), alpha' = 1, over one view's
// RGBA16F pixels. L is scene::EnvironmentMap::radiance, written again here: rotation about +Y,
// u = 0.5 + atan2(x, -z) / 2pi, v = acos(y) / pi, bilinear between texel centres, u wrapping,
// v clamped.
#version 460

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) buffer Hdr { uvec2 hdr[]; };
layout(std430, set = 0, binding = 1) readonly buffer Map { vec4 texels[]; };

layout(push_constant) uniform Params {
  mat4 inv_view_proj;
  vec4 eye;
  uvec4 size;  // view width, height, first pixel of the view, map width
  uint map_height;
  float rotation_cos;
  float rotation_sin;
  float pad;
} params;

const float kPi = 3.14159265358979;
const float kHalfMax = 65504.0;

vec3 texel(int x, int y) { return texels[y * int(params.size.w) + x].rgb; }

vec3 environment(vec3 d) {
  const float x = params.rotation_cos * d.x - params.rotation_sin * d.z;
  const float z = params.rotation_sin * d.x + params.rotation_cos * d.z;
  const float u = clamp(0.5 + atan(x, -z) / (2.0 * kPi), 0.0, 1.0);
  const float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
  const int w = int(params.size.w);
  const int h = int(params.map_height);
  const float fx = u * float(w) - 0.5;
  const float fy = clamp(v * float(h) - 0.5, 0.0, float(h - 1));
  const float x0f = floor(fx);
  const float y0f = floor(fy);
  const float tx = fx - x0f;
  const float ty = fy - y0f;
  const int x0 = ((int(x0f) % w) + w) % w;
  const int x1 = (x0 + 1) % w;
  const int y0 = int(y0f);
  const int y1 = min(y0 + 1, h - 1);
  const vec3 top = mix(texel(x0, y0), texel(x1, y0), tx);
  const vec3 bottom = mix(texel(x0, y1), texel(x1, y1), tx);
  return mix(top, bottom, ty);
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint width = params.size.x;
  const uint height = params.size.y;
  if (i >= width * height) return;
  const uint index = params.size.z + i;
  const vec2 rg = unpackHalf2x16(hdr[index].x);
  const vec2 ba = unpackHalf2x16(hdr[index].y);
  const float alpha = clamp(ba.y, 0.0, 1.0);
  if (alpha >= 1.0) return;
  // Row 0 is the top of the image, NDC y = -1 (Vulkan); any depth inside the frustum lies on
  // the pixel's ray.
  const vec2 ndc = (vec2(float(i % width), float(i / width)) + 0.5) / vec2(width, height) * 2.0 - 1.0;
  const vec4 p = params.inv_view_proj * vec4(ndc, 0.5, 1.0);
  const vec3 dir = normalize(p.xyz / p.w - params.eye.xyz);
  const vec3 c = min(vec3(rg, ba.x) + (1.0 - alpha) * environment(dir), vec3(kHalfMax));
  hdr[index] = uvec2(packHalf2x16(c.rg), packHalf2x16(vec2(c.b, 1.0)));
}
