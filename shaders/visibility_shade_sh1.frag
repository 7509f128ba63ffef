// Visibility pass shading with L1 probes, single-sampled (visibility_shade.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 1
#include "visibility_shade.glsl"
