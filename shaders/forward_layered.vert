// Forward pass vertex stage for layered passes: gl_Layer from the instance (forward_vertex.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define FORWARD_LAYERED
#include "forward_vertex.glsl"
