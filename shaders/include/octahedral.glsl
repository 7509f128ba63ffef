// The octahedral map of directions onto an R x R grid of texels (probes/moment_map.h): the
// GPU probe tracer bins its first-hit distances with it (probe_project.comp), so its moment
// maps have exactly the CPU tracer's texels, and the rasterizer reads the maps with it
// (probe_lighting.glsl).
#ifndef DDISH_OCTAHEDRAL_GLSL
#define DDISH_OCTAHEDRAL_GLSL

// Texel (row-major, x fastest) of an R x R map holding unit direction d (probes::moment_texel):
// d / |d|_1 onto the square, the lower hemisphere folded over the diagonals with a sign that
// is never 0, so directions on the coordinate planes fold as the CPU folds them.
uint octahedral_texel(vec3 d, uint res) {
  const float l1 = abs(d.x) + abs(d.y) + abs(d.z);
  vec2 p = l1 > 0.0 ? d.xy / l1 : vec2(0.0);
  if (d.z < 0.0) {
    const vec2 s = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    p = (1.0 - abs(p.yx)) * s;
  }
  const vec2 uv = p * 0.5 + 0.5;
  const int last = int(res) - 1;
  const int x = clamp(int(uv.x * float(res)), 0, last);
  const int y = clamp(int(uv.y * float(res)), 0, last);
  return uint(x) + res * uint(y);
}

#endif  // DDISH_OCTAHEDRAL_GLSL
