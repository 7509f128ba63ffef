// Test helper: where a world point (or a direction, w = 0) lands in a view, in continuous pixel
// coordinates ((0, 0) = top-left corner, as scene::view_ray counts them). Done in double from
// the view's float matrices so the test measures the matrices, not the arithmetic.
#pragma once

#include <glm/glm.hpp>

#include "scene/view.h"

namespace ddish::display::test {

inline glm::dvec2 project(const scene::View& v, const glm::dvec4& point) {
  const glm::dmat4 m = glm::dmat4(v.projection) * glm::dmat4(v.view);
  const glm::dvec4 clip = m * point;
  const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
  return glm::dvec2((ndc.x + 1.0) * 0.5 * v.width, (ndc.y + 1.0) * 0.5 * v.height);
}

inline glm::dvec2 project_point(const scene::View& v, const glm::vec3& p) {
  return project(v, glm::dvec4(glm::dvec3(p), 1.0));
}

inline glm::dvec2 project_direction(const scene::View& v, const glm::vec3& d) {
  return project(v, glm::dvec4(glm::dvec3(d), 0.0));
}

}  // namespace ddish::display::test
