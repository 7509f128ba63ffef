// Forward pass vertex stage for per-view and multiview passes (see forward_vertex.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "forward_vertex.glsl"
