// The live window's probe-grid overlay (display/gpu_compositor.h): marks world points (the
// probes) in every gathered view before the composition, so every display mode shows them, the
// lenticular panel image included (each view gets its own projection: the dots have parallax).
// One invocation per (point, view): the point is projected by the view's matrix (Vulkan
// convention, NDC y down the image) and a 3 × 3 dot of its colour written where it lands. No
// depth test: the overlay shows the whole grid, hidden probes too.
#version 450

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) buffer Views { uint views[]; };  // view after view
layout(std430, set = 0, binding = 1) readonly buffer Points { vec4 points[]; };  // xyz, w: colour
layout(std430, set = 0, binding = 2) readonly buffer Matrices { mat4 view_projection[]; };

layout(push_constant) uniform Params {
  uint point_count;
  uint view_count;
  uint width;  // one view
  uint height;
} p;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= p.point_count * p.view_count) return;
  const uint point = i % p.point_count;
  const uint view = i / p.point_count;
  const vec4 clip = view_projection[view] * vec4(points[point].xyz, 1.0);
  if (clip.w <= 0.0) return;
  const vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z < 0.0 || ndc.z > 1.0) return;
  const ivec2 centre = ivec2((ndc.xy * 0.5 + 0.5) * vec2(p.width, p.height));
  const uint colour = floatBitsToUint(points[point].w);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const ivec2 at = centre + ivec2(dx, dy);
      if (at.x < 0 || at.y < 0 || at.x >= int(p.width) || at.y >= int(p.height)) continue;
      views[(view * p.height + uint(at.y)) * p.width + uint(at.x)] = colour;
    }
}
