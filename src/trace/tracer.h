// The path tracer shared by the probe tracer and the reference renderer ("one path tracer, two
// uses", DESIGN.md): an Embree 3 scene built from the scene model, the glTF BSDF, next-event
// estimation with MIS, environment radiance, Russian roulette. Thread-safe for concurrent
// trace_path calls; deterministic for a given Sampler.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>

#include <glm/glm.hpp>

#include "trace/sampler.h"

namespace ddish::scene {
struct Scene;
}

namespace ddish::trace {

class EmbreeScene;
class RayRecorder;

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  // Ray-cone spread angle (radians) of the footprint this ray stands for: a camera's pixel angle,
  // or a probe's solid angle per sample as sqrt(4 pi / N). Selects texture mip levels; 0 = finest.
  float cone_spread = 0.0f;
};

struct PathOptions {
  int max_bounces = 8;          // surface interactions after the first hit that may scatter
  int rr_min_bounces = 3;       // Russian roulette starts after this many bounces
  float indirect_clamp = 0.0f;  // > 0: clamp each indirect contribution's max channel to this
  int fixed_mip_level = -1;     // >= 0: sample textures at this mip level instead of ray footprint
};

// What one path returns: the radiance arriving at ray.origin from ray.direction, and facts
// about its first hit (probe classification uses them).
struct PathSample {
  glm::vec3 radiance{0.0f};
  bool hit = false;           // the first ray hit a surface
  bool backface = false;      // ... and it hit the back of a single-sided surface
  float hit_distance = std::numeric_limits<float>::infinity();
};

class Tracer {
 public:
  // The scene must outlive the tracer: meshes and texture pixels are read in place, not copied
  // (the tracer adds Embree's BVHs and the textures' smaller mip levels, one third more).
  Tracer(const scene::Scene& scene, const PathOptions& options = {});
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Follows the scene posed at a new time: re-commits the moved instances and refreshes light
  // placements, without rebuilding geometry that did not move (scene::Scene::pose returns them).
  // `scene` is the Scene object the tracer was built from; not while trace_path runs.
  void update(const scene::Scene& scene, std::span<const int> moved_instances);

  PathSample trace_path(const Ray& ray, Sampler& sampler) const;

  const PathOptions& options() const;
  void set_options(const PathOptions& options);  // not while trace_path runs

  // Rays cast so far (primary, bounce and shadow rays), for Mrays/s figures.
  std::uint64_t rays_traced() const;
  void reset_ray_count();
  // Records every ray cast from now on into `recorder` (null: stop); bench/trace_floor replays
  // them as the tracing floor. Not while trace_path runs.
  void set_ray_recorder(RayRecorder* recorder);
  // The Embree scene the paths are traced on, for replaying recorded rays on it.
  const EmbreeScene& embree_scene() const;

  // Paths whose radiance came out NaN, infinite or negative; they return zero radiance instead.
  std::uint64_t invalid_paths() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddish::trace
