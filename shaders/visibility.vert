// Visibility pass geometry, vertex stage for per-view and multiview passes (visibility_vertex.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#include "visibility_vertex.glsl"
