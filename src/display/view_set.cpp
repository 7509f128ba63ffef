#include "display/view_set.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"

namespace ddish::display {

glm::vec3 BaseCamera::axis_forward() const { return glm::normalize(forward); }

glm::vec3 BaseCamera::axis_right() const {
  return glm::normalize(glm::cross(axis_forward(), up));
}

glm::vec3 BaseCamera::axis_up() const { return glm::cross(axis_right(), axis_forward()); }

void BaseCamera::validate() const {
  const float fl = glm::length(forward);
  if (!(fl > 0.0f) || !std::isfinite(fl)) {
    throw std::invalid_argument("camera forward direction is zero or not finite");
  }
  const float ul = glm::length(up);
  if (!(ul > 0.0f) || glm::length(glm::cross(forward / fl, up / ul)) < 1e-6f) {
    throw std::invalid_argument("camera up direction is zero or parallel to forward");
  }
  if (!(fov_y > 0.0f && fov_y < 3.14159f)) {
    throw std::invalid_argument("camera field of view " + std::to_string(fov_y) +
                                " rad is outside (0, pi)");
  }
  if (!(focal_distance > 0.0f) || !std::isfinite(focal_distance)) {
    throw std::invalid_argument("focal distance " + std::to_string(focal_distance) +
                                " must be positive");
  }
  if (!(znear > 0.0f) || !(zfar > znear)) {
    throw std::invalid_argument("clip planes near " + std::to_string(znear) + ", far " +
                                std::to_string(zfar) + " need 0 < near < far");
  }
}

BaseCamera base_camera(const scene::Camera& camera, float focal_distance) {
  BaseCamera b;
  b.eye = camera.eye;
  b.forward = camera.forward;
  b.up = camera.up;
  b.fov_y = camera.yfov;
  b.focal_distance = focal_distance;
  b.znear = camera.znear;
  b.zfar = camera.zfar;
  return b;
}

float focal_distance_to_scene_center(const scene::Scene& scene, const glm::vec3& eye,
                                     const glm::vec3& forward) {
  const scene::Aabb bounds = scene.bounds();
  if (bounds.empty()) return 1.0f;
  const glm::vec3 to_center = bounds.center() - eye;
  const float along = glm::dot(to_center, glm::normalize(forward));
  if (along > 1e-6f) return along;
  const float straight = glm::length(to_center);
  return straight > 1e-6f ? straight : 1.0f;
}

const char* to_string(ViewSetKind kind) {
  switch (kind) {
    case ViewSetKind::Single: return "single";
    case ViewSetKind::Stereo: return "stereo";
    case ViewSetKind::LightField: return "lightfield";
    case ViewSetKind::Grid: return "grid";
  }
  return "unknown";
}

scene::View sheared_view(const BaseCamera& base, float offset_right, float offset_up,
                         float distance, float half_width, float half_height, int width,
                         int height) {
  const glm::vec3 f = base.axis_forward();
  const glm::vec3 r = base.axis_right();
  const glm::vec3 u = base.axis_up();
  const glm::vec3 eye = base.eye + offset_right * r + offset_up * u;

  scene::View v;
  v.view = glm::lookAtRH(eye, eye + f, u);
  // In this camera's space the framed rectangle is centred at (-offset_right, -offset_up) on the
  // plane z = -distance; scaling it onto the near plane gives the off-axis frustum.
  const float s = base.znear / distance;
  v.projection = scene::frustum_vk((-offset_right - half_width) * s,
                                   (-offset_right + half_width) * s,
                                   (-offset_up - half_height) * s, (-offset_up + half_height) * s,
                                   base.znear, base.zfar);
  v.width = width;
  v.height = height;
  return v;
}

std::string indexed_view_name(int index, int count) {
  const std::string last = std::to_string(count > 1 ? count - 1 : 0);
  std::string digits = std::to_string(index);
  if (digits.size() < last.size()) digits.insert(0, last.size() - digits.size(), '0');
  return "view_" + digits;
}

}  // namespace ddish::display
