// What a path ray of the GPU probe tracer reports: the closest hit's triangle and barycentrics
// (t < 0: it escaped). Shared by probe_trace.rgen and its hit and miss shaders.
#ifndef DDISH_TRACE_PAYLOAD_GLSL
#define DDISH_TRACE_PAYLOAD_GLSL

struct PathPayload {
  vec2 bary;  // (u, v): p = (1 - u - v) p0 + u p1 + v p2
  float t;
  uint instance;
  uint prim;
};

#endif  // DDISH_TRACE_PAYLOAD_GLSL
