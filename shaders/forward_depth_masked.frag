// The forward pass's depth prepass for alpha-masked materials (raster/forward_pass.h): no
// colour, only the discard of the pixels the shading pass would discard, from the same base
// colour (forward_material.glsl), so the depth it leaves is exactly what the shading pass's
// depth test then finds. Opaque materials' prepass has no fragment stage at all.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "forward_material.glsl"

void main() {
  if (masked_out(material_base_color().a)) discard;
}
