// The live window's camera: it orbits a target point, pans in the view plane, dollies towards
// the target, and flies (eye and target together). No SDL here (window/input.h turns events into
// these calls), so the numbers are testable on their own. The documented rates:
//   orbit  kOrbitRadiansPerPixel of yaw (about the world up axis) per pixel of horizontal drag,
//          the same of pitch per pixel of vertical drag; pitch stays within ±kMaxPitchDeg
//   pan    the target moves so that a point at the target's depth follows the cursor: one pixel
//          is 2·distance·tan(fov/2) / window height scene units
//   dolly  each wheel step towards the screen multiplies the distance by kDollyPerStep (away:
//          divides), never below kMinDistance
//   fly    kFlyFocusPerSecond target distances per second along the view (W/S), right (D/A)
//          and world up (E/Q)
// The target is the light-field focal plane's distance (app: focal distance = distance()).
#pragma once

#include <glm/glm.hpp>

namespace ddish::window {

inline constexpr float kOrbitRadiansPerPixel = 0.005f;
inline constexpr float kMaxPitchDeg = 89.0f;
inline constexpr float kDollyPerStep = 0.9f;
inline constexpr float kMinDistance = 1e-3f;
inline constexpr float kFlyFocusPerSecond = 1.0f;

class OrbitCamera {
 public:
  // Looks from `eye` at `target` with world up `up`; fov_y in radians. Throws
  // std::invalid_argument when eye equals target or up is parallel to the view.
  OrbitCamera(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fov_y);

  void orbit(float dx_pixels, float dy_pixels);
  void pan(float dx_pixels, float dy_pixels, int window_height);
  void dolly(float steps);  // > 0: towards the target
  // Directions in the camera frame (x right, y world up, z forward), each in −1..1.
  void fly(const glm::vec3& direction, float seconds);

  glm::vec3 eye() const;
  glm::vec3 forward() const;
  const glm::vec3& target() const { return target_; }
  const glm::vec3& up() const { return up_; }
  glm::vec3 right() const;
  float distance() const { return distance_; }
  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  float fov_y() const { return fov_y_; }
  // Whether anything moved since the last call (the views then differ from last frame's).
  bool take_moved();

 private:
  glm::vec3 target_;
  glm::vec3 up_;
  glm::vec3 yaw_zero_;  // the horizontal direction yaw 0 faces
  float distance_;
  float yaw_ = 0.0f;
  float pitch_ = 0.0f;
  float fov_y_;
  bool moved_ = false;
};

}  // namespace ddish::window
