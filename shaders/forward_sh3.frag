// Forward pass fragment shader with L3 probes (forward_main.glsl has the shading).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 3
#include "forward_main.glsl"
