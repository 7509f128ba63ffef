// Warping functions: maps from uniform points u in [0,1)^2 to common distributions, each with its
// density. Directions are unit vectors in a local frame where z is the axis (the normal, or the
// cone's centre); densities are per unit solid angle (per unit area for the disk and triangle).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace ddish::trace {

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = std::numbers::inv_pi_v<float>;

// Unit disk, uniform per area, by Shirley and Chiu's concentric map: it keeps strata compact
// (no squeezing at the centre), so stratified u stays stratified on the disk.
inline glm::vec2 sample_uniform_disk(const glm::vec2& u) {
  const float a = 2.0f * u.x - 1.0f;
  const float b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) {
    return {0.0f, 0.0f};
  }
  float r;
  float phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = (kPi / 4.0f) * (b / a);
  } else {
    r = b;
    phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}
inline float uniform_disk_pdf() { return kInvPi; }

// Hemisphere z >= 0 with density cos(theta) / pi (Malley's method: lift the uniform disk).
inline glm::vec3 sample_cosine_hemisphere(const glm::vec2& u) {
  const glm::vec2 d = sample_uniform_disk(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

// Hemisphere z >= 0, uniform: density 1 / (2 pi).
inline glm::vec3 sample_uniform_hemisphere(const glm::vec2& u) {
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_hemisphere_pdf() { return 0.5f * kInvPi; }

// Whole sphere, uniform: density 1 / (4 pi).
inline glm::vec3 sample_uniform_sphere(const glm::vec2& u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_sphere_pdf() { return 0.25f * kInvPi; }

// Cone of directions within acos(cos_max) of +z, uniform: density 1 / (2 pi (1 - cos_max)).
// (For lights of finite angular size: a sun disk, a distant sphere.)
inline glm::vec3 sample_uniform_cone(const glm::vec2& u, float cos_max) {
  const float z = 1.0f - u.x * (1.0f - cos_max);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_cone_pdf(float cos_max) { return 1.0f / (2.0f * kPi * (1.0f - cos_max)); }

// Triangle, uniform per area: returns barycentrics (b0, b1); the point is
// b0 * p0 + b1 * p1 + (1 - b0 - b1) * p2 and its density is 1 / area.
inline glm::vec2 sample_uniform_triangle(const glm::vec2& u) {
  const float s = std::sqrt(u.x);
  return {1.0f - s, u.y * s};
}

}  // namespace ddish::trace
