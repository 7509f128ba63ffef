// The rays a Tracer casts, recorded for replay: bench/trace_floor traces an update's own rays
// (closest-hit queries for camera, probe and bounce rays; occlusion queries for shadow rays) with
// plain Embree calls and no shading, which is the floor the full update is measured against.
// Recording is off unless a recorder is attached (Tracer::set_ray_recorder); then every cast is
// appended to the calling thread's own list, in the order that thread cast it (path by path), so
// a replay over the same threads sees the same coherence.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/enumerable_thread_specific.h>

namespace ddish::trace {

struct RecordedRay {
  glm::vec3 origin{0.0f};
  float tmin = 0.0f;
  glm::vec3 direction{0.0f};
  float tmax = 0.0f;
  // What the alpha filters read (embree_scene.h's RayQuery), so a replay on the tracer's own
  // Embree scene takes the same filter decisions.
  std::uint32_t alpha_seed = 0;
  float cone_width = 0.0f;
  float cone_spread = 0.0f;
  bool occlusion = false;  // a shadow ray (any hit ends it), else a closest-hit query
};

class RayRecorder {
 public:
  void record(const RecordedRay& ray) { lists_.local().push_back(ray); }
  // Every ray recorded so far, thread after thread (each thread's in its casting order); the
  // recorder is empty afterwards.
  std::vector<RecordedRay> take();

 private:
  tbb::enumerable_thread_specific<std::vector<RecordedRay>> lists_;
};

}  // namespace ddish::trace
