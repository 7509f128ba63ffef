// Shadow pass for alpha-masked materials (foliage, fences): like shadow.vert, plus the UV sets and
// the vertex colour's alpha that shadow_masked.frag needs to cut the caster's holes out of the map.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 0) out vec4 out_uv;  // xy: TEXCOORD_0, zw: TEXCOORD_1
layout(location = 1) out float out_alpha;

void main() {
  out_uv = vec4(in_uv, in_uv1);
  out_alpha = in_color.a;
  gl_Position = shadow_layers[pc.view_index].light_view_proj * (pc.model * vec4(in_position, 1.0));
}
