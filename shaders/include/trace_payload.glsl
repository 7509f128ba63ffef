// What the GPU probe tracer's rays carry. A path ray reports the closest hit's triangle and
// barycentrics (t < 0: it escaped); a shadow ray whether it reached its end. Both carry what
// the any-hit shaders need for alpha: a per-ray seed (BLEND transparency) and the ray cone
// (the base colour's mip level). Shared by probe_trace.rgen and its hit and miss shaders.
#ifndef DDISH_TRACE_PAYLOAD_GLSL
#define DDISH_TRACE_PAYLOAD_GLSL

struct PathPayload {
  vec2 bary;  // (u, v): p = (1 - u - v) p0 + u p1 + v p2
  float t;
  uint instance;
  uint prim;
  uint alpha_seed;
  float cone_width;  // at the ray's origin, metres
  float spread;      // radians
};

struct ShadowPayload {
  uint visible;
  uint alpha_seed;
  float cone_width;
  float spread;
};

#endif  // DDISH_TRACE_PAYLOAD_GLSL
