#version 460
// The GPU probe tracer's miss for shadow rays: nothing was in the way.
#extension GL_EXT_ray_tracing : require

layout(location = 1) rayPayloadInEXT uint unoccluded;

void main() { unoccluded = 1u; }
