// Forward pass, vertex stage (the body of forward.vert and forward_layered.vert): object ->
// world -> clip for one view. Per-instance transforms arrive as push constants (instances share
// their mesh's vertex buffer). Which view a vertex is for depends on how the views are recorded
// (raster/view_method.h):
//   per-view and multiview passes: views[pc.view_index + gl_ViewIndex] (gl_ViewIndex is 0
//     outside multiview, and pc.view_index is the pass's first view);
//   layered (FORWARD_LAYERED): the draw's instance is its view, written to gl_Layer.
// The view index goes to the fragment stage as a flat varying, so both stages agree whatever
// the method.
// Not compiled on its own: the .vert files set #version and FORWARD_LAYERED and include this.
#ifdef FORWARD_LAYERED
#extension GL_ARB_shader_viewport_layer_array : require
#else
#extension GL_EXT_multiview : require
#endif
#include "raster_common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;  // COLOR_0 (white without vertex colours)

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec4 out_uv;  // xy: TEXCOORD_0, zw: TEXCOORD_1
layout(location = 3) out vec4 out_tangent;
layout(location = 4) flat out uint out_view;
layout(location = 5) out vec4 out_color;

void main() {
#ifdef FORWARD_LAYERED
  const uint view = uint(gl_InstanceIndex);
  gl_Layer = gl_InstanceIndex;
#else
  const uint view = pc.view_index + uint(gl_ViewIndex);
#endif
  const vec4 world = pc.model * vec4(in_position, 1.0);
  out_world = world.xyz;
  // Normals take the inverse transpose (computed on the CPU, per instance, not per vertex:
  // vertex work is what a CPU rasterizer pays for).
  const mat3 normal_matrix = mat3(pc.normal_matrix[0].xyz, pc.normal_matrix[1].xyz,
                                  pc.normal_matrix[2].xyz);
  out_normal = normal_matrix * in_normal;
  out_tangent = vec4(mat3(pc.model) * in_tangent.xyz, in_tangent.w * pc.normal_matrix[0].w);
  out_uv = vec4(in_uv, in_uv1);
  out_color = in_color;
  out_view = view;
  gl_Position = views[view].view_proj * world;
}
