#include "scene/framing.h"

#include <algorithm>
#include <cmath>

namespace ddish::scene {

Sphere bounding_sphere(const Scene& scene) {
  const Aabb box = scene.bounds();
  Sphere s;
  if (box.empty()) return s;
  s.center = box.center();
  float r2 = 0.0f;
  for (const Instance& inst : scene.instances) {
    const Mesh& mesh = scene.meshes[std::size_t(inst.mesh)];
    for (const glm::vec3& p : mesh.positions) {
      const glm::vec3 d = glm::vec3(inst.transform * glm::vec4(p, 1.0f)) - s.center;
      r2 = std::max(r2, glm::dot(d, d));
    }
  }
  s.radius = std::sqrt(r2);
  return s;
}

Camera framing_camera(const Sphere& sphere, float yfov, float aspect) {
  const float radius = sphere.radius > 0.0f ? sphere.radius : 1.0f;
  // The narrower half-field: vertical for landscape images, horizontal for portrait ones.
  const float half_y = 0.5f * yfov;
  const float half = std::min(half_y, std::atan(std::tan(half_y) * aspect));
  // A sphere at distance d subtends the half-angle asin(r / d) and its silhouette reaches
  // tan(asin(r / d)) on the image plane at distance 1; kFramingFill of the half-field there.
  const float alpha = std::atan(kFramingFill * std::tan(half));
  const float distance = radius / std::sin(alpha);
  const float az = glm::radians(kFramingAzimuthDeg);
  const float el = glm::radians(kFramingElevationDeg);
  const glm::vec3 toward_eye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  Camera c;
  c.name = kFramingCameraName;
  c.yfov = yfov;
  c.node = -1;
  c.eye = sphere.center + distance * toward_eye;
  c.forward = -toward_eye;
  c.up = glm::vec3(0.0f, 1.0f, 0.0f);
  // The whole sphere lies between distance - r and distance + r from the eye.
  c.znear = 0.5f * (distance - radius);
  c.zfar = 2.0f * (distance + radius);
  return c;
}

}  // namespace ddish::scene
