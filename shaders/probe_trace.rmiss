#version 460
// The GPU probe tracer's miss for path rays: t < 0 says the ray escaped to the sky.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "trace_payload.glsl"

layout(location = 0) rayPayloadInEXT PathPayload hit;

void main() { hit.t = -1.0; }
