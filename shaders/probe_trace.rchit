#version 460
// The GPU probe tracer's closest hit: reports the triangle; probe_trace.rgen shades it.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "trace_payload.glsl"

layout(location = 0) rayPayloadInEXT PathPayload hit;
hitAttributeEXT vec2 bary;

void main() {
  hit.bary = bary;
  hit.t = gl_HitTEXT;
  hit.instance = gl_InstanceCustomIndexEXT;
  hit.prim = gl_PrimitiveID;
}
