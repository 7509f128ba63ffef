#include "scene/view.h"

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"

namespace ddish::scene {

glm::mat4 frustum_vk(float left, float right, float bottom, float top, float znear, float zfar) {
  // Maps camera-space (x, y, z<0) to clip space with depth in [0, 1] and NDC y growing downwards
  // (Vulkan's framebuffer convention), so image row 0 is the top of the view.
  glm::mat4 m(0.0f);
  m[0][0] = 2.0f * znear / (right - left);
  m[1][1] = -2.0f * znear / (top - bottom);
  m[2][0] = (right + left) / (right - left);
  m[2][1] = -(top + bottom) / (top - bottom);
  m[2][2] = zfar / (znear - zfar);
  m[2][3] = -1.0f;
  m[3][2] = znear * zfar / (znear - zfar);
  return m;
}

glm::mat4 perspective_vk(float fov_y, float aspect, float znear, float zfar) {
  float top = znear * std::tan(0.5f * fov_y);
  float right = top * aspect;
  return frustum_vk(-right, right, -top, top, znear, zfar);
}

View look_at_view(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fov_y,
                  int width, int height, float znear, float zfar) {
  View v;
  v.view = glm::lookAtRH(eye, target, up);
  v.projection = perspective_vk(fov_y, float(width) / float(height), znear, zfar);
  v.width = width;
  v.height = height;
  return v;
}

View camera_view(const Camera& camera, int width, int height) {
  View v = look_at_view(camera.eye, camera.eye + camera.forward, camera.up, camera.yfov, width,
                        height, camera.znear, camera.zfar);
  v.name = camera.name;
  return v;
}

Ray view_ray(const View& v, float px, float py) {
  glm::vec2 ndc(2.0f * px / float(v.width) - 1.0f, 2.0f * py / float(v.height) - 1.0f);
  glm::mat4 inv = glm::inverse(v.projection * v.view);
  glm::vec4 near_h = inv * glm::vec4(ndc, 0.0f, 1.0f);
  glm::vec3 near_p = glm::vec3(near_h) / near_h.w;
  glm::vec3 eye = v.eye();
  // Rays start at the eye (pinhole); the direction goes through the pixel on the near plane.
  return Ray{eye, glm::normalize(near_p - eye)};
}

}  // namespace ddish::scene
