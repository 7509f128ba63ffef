#include "xr/eye_views.h"

#include <glm/gtc/quaternion.hpp>

#include "display/stereo.h"

namespace ddish::xr {

scene::View eye_view(const display::BaseCamera& origin, const XrPosef& eye, const XrFovf& fov, int width,
                     int height) {
  // LOCAL axes in the scene: x right, y up, -z forward of the base camera.
  const glm::mat3 local_to_world(origin.axis_right(), origin.axis_up(), -origin.axis_forward());
  const glm::quat q(eye.orientation.w, eye.orientation.x, eye.orientation.y, eye.orientation.z);
  display::BaseCamera camera = origin;
  camera.eye = origin.eye + local_to_world * glm::vec3(eye.position.x, eye.position.y, eye.position.z);
  camera.forward = local_to_world * (q * glm::vec3(0.0f, 0.0f, -1.0f));
  camera.up = local_to_world * (q * glm::vec3(0.0f, 1.0f, 0.0f));
  const display::EyeFov angles{fov.angleLeft, fov.angleRight, fov.angleUp, fov.angleDown};
  return display::fov_view(camera, 0.0f, angles, width, height);
}

}  // namespace ddish::xr
