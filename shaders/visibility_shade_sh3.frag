// Visibility pass shading with L3 probes, single-sampled (visibility_shade.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 3
#include "visibility_shade.glsl"
