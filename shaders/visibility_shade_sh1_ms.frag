// Visibility pass shading with L1 probes, multisampled ids (visibility_shade.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 1
#define VISIBILITY_MULTISAMPLED 1
#include "visibility_shade.glsl"
