// Axis-aligned bounding box.
#pragma once

#include <limits>

#include <glm/glm.hpp>

namespace ddish::scene {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  void expand(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  void expand(const Aabb& b) { if (!b.empty()) { expand(b.min); expand(b.max); } }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : max - min; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  bool contains(const glm::vec3& p) const {
    return glm::all(glm::greaterThanEqual(p, min)) && glm::all(glm::lessThanEqual(p, max));
  }
  // The box of this box's 8 corners under an affine transform.
  Aabb transformed(const glm::mat4& m) const {
    Aabb out;
    if (empty()) return out;
    for (int i = 0; i < 8; ++i) {
      glm::vec3 c((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
      out.expand(glm::vec3(m * glm::vec4(c, 1.0f)));
    }
    return out;
  }
};

}  // namespace ddish::scene
