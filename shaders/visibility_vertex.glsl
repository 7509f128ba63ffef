// Visibility pass, geometry vertex stage (the body of visibility.vert and
// visibility_layered.vert): object -> world -> clip for one view, as forward_vertex.glsl places
// it, plus the UVs and COLOR_0 that an alpha-masked material's coverage needs
// (visibility_masked.frag). The view, by recording method (raster/view_method.h):
//   per-view and multiview passes: views[pc.view_index + gl_ViewIndex];
//   layered (VISIBILITY_LAYERED): the draw's instance is its view, written to gl_Layer.
#ifdef VISIBILITY_LAYERED
#extension GL_ARB_shader_viewport_layer_array : require
#else
#extension GL_EXT_multiview : require
#endif
#include "raster_common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 2) out vec4 out_uv;  // xy: TEXCOORD_0, zw: TEXCOORD_1 (forward_material.glsl)
layout(location = 5) out vec4 out_color;

void main() {
#ifdef VISIBILITY_LAYERED
  const uint view = uint(gl_InstanceIndex);
  gl_Layer = gl_InstanceIndex;
#else
  const uint view = pc.view_index + uint(gl_ViewIndex);
#endif
  out_uv = vec4(in_uv, in_uv1);
  out_color = in_color;
  gl_Position = views[view].view_proj * (pc.model * vec4(in_position, 1.0));
}
