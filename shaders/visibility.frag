// Visibility pass geometry, opaque materials: what each sample sees, as (scene instance,
// triangle of GpuMeshes' index buffer). No discard, so depth is tested before the shader.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"

layout(location = 0) out uvec2 out_id;

// The instance's top bit says the sample sees the triangle's back (visibility_shade.glsl).
void main() {
  out_id = uvec2(pc.instance | (gl_FrontFacing ? 0u : 0x80000000u), pc.first_triangle + uint(gl_PrimitiveID));
}
