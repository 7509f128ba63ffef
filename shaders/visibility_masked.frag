// Visibility pass geometry, alpha-masked materials: the pixels below the cutoff are discarded
// from the same base colour as the forward shading decides it (forward_material.glsl), at the
// pixel centre, so a pixel's samples are covered or not as in the forward pass.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"
#include "forward_material.glsl"

layout(location = 0) out uvec2 out_id;

void main() {
  if (masked_out(material_base_color().a)) discard;
  out_id = uvec2(pc.instance | (gl_FrontFacing ? 0u : 0x80000000u), pc.first_triangle + uint(gl_PrimitiveID));
}
