// View frusta for probe scheduling: the six planes of a view's projection * view matrix in
// Vulkan clip conventions (-w <= x, y <= w, 0 <= z <= w), normalised so that a plane's value at
// a point is its signed distance in metres (positive inside). The scheduler asks whether the
// box of cells a probe influences meets any view's frustum, with a margin in metres that
// widens every plane outwards: a probe just outside the view now is inside it after a small
// camera motion, and its light should be fresh by then.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "scene/aabb.h"
#include "scene/view.h"

namespace ddish::probes {

struct Plane {
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit length, pointing into the frustum
  float d = 0.0f;

  float distance(const glm::vec3& p) const { return glm::dot(normal, p) + d; }
};

class Frustum {
 public:
  Frustum() = default;
  // The frustum of clip = projection * view; perspective or orthographic.
  explicit Frustum(const glm::mat4& clip_from_world);
  explicit Frustum(const scene::View& view) : Frustum(view.projection * view.view) {}

  // left, right, bottom, top, near, far (bottom/top as NDC y, which points down in Vulkan).
  const std::array<Plane, 6>& planes() const { return planes_; }

  // Whether the box may meet the frustum widened by margin metres on every side. Conservative:
  // a box that misses it diagonally past an edge can still count as meeting it (the usual
  // plane test), which only schedules a probe a little early, never leaves one out.
  bool intersects(const scene::Aabb& box, float margin = 0.0f) const;
  bool contains(const glm::vec3& point, float margin = 0.0f) const;

 private:
  std::array<Plane, 6> planes_{};
};

}  // namespace ddish::probes
