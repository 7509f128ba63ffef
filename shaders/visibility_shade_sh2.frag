// Visibility pass shading with L2 probes, single-sampled (visibility_shade.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 2
#include "visibility_shade.glsl"
