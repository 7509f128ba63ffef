// Shadow pass for alpha-masked materials (foliage, fences): like shadow.vert, plus the UV that
// shadow_masked.frag needs to cut the caster's holes out of the map.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec2 out_uv;

void main() {
  out_uv = in_uv;
  gl_Position = shadow_layers[pc.view_index].light_view_proj * (pc.model * vec4(in_position, 1.0));
}
