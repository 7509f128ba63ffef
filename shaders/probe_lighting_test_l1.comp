// The probe-lighting test harness (probe_lighting_test.glsl) at SH order 1.
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 1
#include "probe_lighting_test.glsl"
