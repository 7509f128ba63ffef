// View sets for the multi-view tests: a horizontal light-field rig in the shape the display
// module builds (cameras moved along the right axis, off-axis frusta sharing one focal plane)
// made here from scene::frustum_vk, so the raster tests need nothing of src/display.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"
#include "scene/view.h"

namespace ddish::raster::test {

// `count` views of width × height around `camera`, spread over `baseline` along its right axis;
// every view frames the focal-plane rectangle at `focal` in front of the camera.
inline std::vector<scene::View> rig_views(const scene::Camera& camera, int count, float baseline,
                                          float focal, int width, int height) {
  const glm::vec3 forward = glm::normalize(camera.forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const float aspect = float(width) / float(height);
  const float top = camera.znear * std::tan(0.5f * camera.yfov);
  std::vector<scene::View> views;
  for (int i = 0; i < count; ++i) {
    const float offset = count > 1 ? baseline * (float(i) / float(count - 1) - 0.5f) : 0.0f;
    const glm::vec3 eye = camera.eye + right * offset;
    // The focal-plane rectangle stays put: the near-plane window slides against the camera.
    const float shift = -offset * camera.znear / focal;
    scene::View v;
    v.view = glm::lookAt(eye, eye + forward, camera.up);
    v.projection = scene::frustum_vk(-top * aspect + shift, top * aspect + shift, -top, top,
                                     camera.znear, camera.zfar);
    v.width = width;
    v.height = height;
    views.push_back(v);
  }
  return views;
}

}  // namespace ddish::raster::test
