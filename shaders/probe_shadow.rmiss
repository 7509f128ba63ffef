#version 460
// The GPU probe tracer's miss for shadow rays: nothing was in the way.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "trace_payload.glsl"

layout(location = 1) rayPayloadInEXT ShadowPayload shadow;

void main() { shadow.visible = 1u; }
