// Visibility pass geometry, vertex stage for layered passes (visibility_vertex.glsl).
#version 460
#extension GL_GOOGLE_include_directive : enable
#define VISIBILITY_LAYERED
#include "visibility_vertex.glsl"
