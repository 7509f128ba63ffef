// A view: where a camera is and what it projects, for one image of width × height pixels.
// Every renderer (reference path tracer, rasterizer) and every view set (single, stereo,
// light-field rig) speaks in Views, so one view, two eyes and N light-field views are the same.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace ddish::scene {

struct Camera;

struct View {
  std::string name;
  glm::mat4 view{1.0f};        // world to camera (right-handed, camera looks down -Z)
  glm::mat4 projection{1.0f};  // camera to clip, Vulkan conventions: depth 0..1, y down in NDC
  int width = 0;
  int height = 0;

  glm::vec3 eye() const { return glm::vec3(glm::inverse(view)[3]); }
};

// A symmetric perspective view looking from eye at target. fov_y in radians.
View look_at_view(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fov_y,
                  int width, int height, float znear = 0.01f, float zfar = 1000.0f);

// The view of a scene camera (its pose at the scene's current time); the aspect comes from
// width / height, not from the camera, so any image size frames the same vertical field.
View camera_view(const Camera& camera, int width, int height);

// Vulkan-convention perspective projection (depth 0..1, NDC y pointing down the image).
glm::mat4 perspective_vk(float fov_y, float aspect, float znear, float zfar);

// Off-axis projection of the frustum whose near-plane rectangle is [left,right]×[bottom,top].
glm::mat4 frustum_vk(float left, float right, float bottom, float top, float znear, float zfar);

// The world-space ray through pixel coordinate (px, py) (continuous, (0,0) = top-left corner of
// the image): origin on the near plane's eye point and a unit direction.
struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;
};
Ray view_ray(const View& v, float px, float py);

}  // namespace ddish::scene
