#include "window/orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ddish::window {

namespace {
constexpr float kMaxPitch = kMaxPitchDeg * 3.14159265358979f / 180.0f;
}

OrbitCamera::OrbitCamera(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up,
                         float fov_y)
    : target_(target), up_(glm::normalize(up)), distance_(glm::length(target - eye)), fov_y_(fov_y) {
  if (!(distance_ > 0.0f)) throw std::invalid_argument("the camera's eye is its target");
  const glm::vec3 f = (target - eye) / distance_;
  const float along_up = glm::dot(f, up_);
  const glm::vec3 horizontal = f - along_up * up_;
  if (glm::length(horizontal) < 1e-6f)
    throw std::invalid_argument("the camera looks along its up axis: no orbit is defined");
  yaw_zero_ = glm::normalize(horizontal);
  pitch_ = std::asin(std::clamp(along_up, -1.0f, 1.0f));
  pitch_ = std::clamp(pitch_, -kMaxPitch, kMaxPitch);
}

glm::vec3 OrbitCamera::forward() const {
  // yaw turns yaw_zero_ about up_ (right-handed), pitch lifts it towards up_.
  const glm::vec3 side = glm::cross(yaw_zero_, up_);
  const glm::vec3 h = std::cos(yaw_) * yaw_zero_ - std::sin(yaw_) * side;
  return std::cos(pitch_) * h + std::sin(pitch_) * up_;
}

glm::vec3 OrbitCamera::right() const { return glm::normalize(glm::cross(forward(), up_)); }

glm::vec3 OrbitCamera::eye() const { return target_ - distance_ * forward(); }

void OrbitCamera::orbit(float dx, float dy) {
  yaw_ += dx * kOrbitRadiansPerPixel;
  pitch_ = std::clamp(pitch_ + dy * kOrbitRadiansPerPixel, -kMaxPitch, kMaxPitch);
  moved_ = moved_ || dx != 0.0f || dy != 0.0f;
}

void OrbitCamera::pan(float dx, float dy, int window_height) {
  if (window_height <= 0) return;
  const float per_pixel = 2.0f * distance_ * std::tan(0.5f * fov_y_) / float(window_height);
  const glm::vec3 camera_up = glm::cross(right(), forward());
  // Dragging right moves the scene right: the target moves left; dragging down (SDL y grows
  // downwards) moves the scene down: the target moves up.
  target_ += (-dx * right() + dy * camera_up) * per_pixel;
  moved_ = moved_ || dx != 0.0f || dy != 0.0f;
}

void OrbitCamera::dolly(float steps) {
  distance_ = std::max(kMinDistance, distance_ * std::pow(kDollyPerStep, steps));
  moved_ = moved_ || steps != 0.0f;
}

void OrbitCamera::fly(const glm::vec3& d, float seconds) {
  if (d == glm::vec3(0.0f) || !(seconds > 0.0f)) return;
  const float step = kFlyFocusPerSecond * distance_ * seconds;
  target_ += (d.x * right() + d.y * up_ + d.z * forward()) * step;
  moved_ = true;
}

bool OrbitCamera::take_moved() { return std::exchange(moved_, false); }

}  // namespace ddish::window
