// Forward pass, vertex stage: object -> world -> clip for one view. Per-instance transforms
// arrive as push constants (instances share their mesh's vertex buffer); the view comes from
// the views buffer, indexed by a push constant today and by gl_ViewIndex once views are
// rendered with multiview (the layout already allows it).
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;

void main() {
  const vec4 world = pc.model * vec4(in_position, 1.0);
  out_world = world.xyz;
  // Normals take the inverse transpose (computed on the CPU, per instance, not per vertex:
  // vertex work is what a CPU rasterizer pays for).
  const mat3 normal_matrix = mat3(pc.normal_matrix[0].xyz, pc.normal_matrix[1].xyz,
                                  pc.normal_matrix[2].xyz);
  out_normal = normal_matrix * in_normal;
  out_tangent = vec4(mat3(pc.model) * in_tangent.xyz, in_tangent.w * pc.normal_matrix[0].w);
  out_uv = in_uv;
  gl_Position = views[pc.view_index].view_proj * world;
}
