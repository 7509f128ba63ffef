// Shadow pass: depth only, one draw per instance per shadow-map layer (a cascade, a spot
// light's map, or one face of a point light's cube). The layer's matrix is chosen by the push
// constant's view_index.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"

layout(location = 0) in vec3 in_position;

void main() {
  gl_Position = shadow_layers[pc.view_index].light_view_proj * (pc.model * vec4(in_position, 1.0));
}
