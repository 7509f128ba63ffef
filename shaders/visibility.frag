// Visibility pass geometry, opaque materials: what each sample sees, as (scene instance,
// triangle of GpuMeshes' index buffer). No discard, so depth is tested before the shader.
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "raster_common.glsl"

layout(location = 0) out uvec2 out_id;

void main() { out_id = uvec2(pc.instance, pc.first_triangle + uint(gl_PrimitiveID)); }
