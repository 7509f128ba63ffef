// Alpha testing in the GPU probe tracer's any-hit shaders, as trace/embree_scene.cpp's filter
// does it: MASK keeps a hit whose alpha (base colour factor x COLOR_0 x texture, at the ray
// cone's mip level without the obliquity term) reaches the cutoff; BLEND keeps it with
// probability alpha (a uniform number from the ray's seed and the triangle), and a single-sided
// BLEND surface seen from behind is not there at all. Needs trace_scene.glsl, trace_texture.glsl.
#ifndef DDISH_TRACE_ALPHA_GLSL
#define DDISH_TRACE_ALPHA_GLSL

uint alpha_hash(uint v) {
  const uint state = v * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

bool alpha_keeps(uint instance_index, uint prim, vec2 bary, float t, vec3 direction, uint seed, float cone_width,
                 float spread) {
  const TraceInstance inst = instances[instance_index];
  const TraceMaterial mat = materials[meshes[inst.mesh].material];
  const TriangleVertices tv = triangle_vertices(instance_index, prim);
  const vec3 p0 = (inst.object_to_world * vec4(tv.v0.position_u.xyz, 1.0)).xyz;
  const vec3 p1 = (inst.object_to_world * vec4(tv.v1.position_u.xyz, 1.0)).xyz;
  const vec3 p2 = (inst.object_to_world * vec4(tv.v2.position_u.xyz, 1.0)).xyz;
  const vec3 c = cross(p1 - p0, p2 - p0);
  const bool blend = (mat.flags & MATERIAL_BLEND) != 0u;
  if (blend && (mat.flags & MATERIAL_DOUBLE_SIDED) == 0u) {
    const vec3 ng = inst.mirrored != 0u ? -c : c;
    if (dot(ng, direction) > 0.0) return false;
  }
  const vec3 w = vec3(1.0 - bary.x - bary.y, bary.x, bary.y);
  float alpha = mat.base_color.a * (tv.v0.color.a * w.x + tv.v1.color.a * w.y + tv.v2.color.a * w.z);
  if (mat.base_color_texture.texture >= 0)
    alpha *= slot_sample(mat.base_color_texture, tv, w, cone_width + spread * t, 1.0, 0.5 * length(c), false).a;
  if (!blend) return alpha >= mat.alpha_cutoff;
  const uint h = alpha_hash(seed ^ alpha_hash(instance_index * 0x9E3779B1u ^ alpha_hash(prim)));
  return float(h >> 8) * (1.0 / 16777216.0) < alpha;
}

#endif  // DDISH_TRACE_ALPHA_GLSL
