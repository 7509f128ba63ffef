// Forward pass fragment shader with L4 probes after a depth prepass (forward_main.glsl has the
// shading; FORWARD_AFTER_PREPASS there says what changes).
#version 460
#extension GL_GOOGLE_include_directive : enable
#extension GL_ARB_post_depth_coverage : require
#define PROBE_SH_ORDER 4
#define FORWARD_AFTER_PREPASS 1
#include "forward_main.glsl"
