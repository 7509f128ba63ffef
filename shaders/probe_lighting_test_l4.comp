// The probe-lighting test harness (probe_lighting_test.glsl) at SH order 4.
#version 460
#extension GL_GOOGLE_include_directive : enable
#define PROBE_SH_ORDER 4
#include "probe_lighting_test.glsl"
