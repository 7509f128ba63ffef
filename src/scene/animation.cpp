#include "scene/animation.h"

#include <algorithm>
#include <cmath>

namespace ddish::scene {

namespace {

// Spherical interpolation of unit quaternions (xyzw) along the shorter arc; falls back to a
// normalised lerp where the two are nearly parallel and the slerp weights lose precision.
glm::vec4 slerp(glm::vec4 a, glm::vec4 b, float s) {
  float d = glm::dot(a, b);
  if (d < 0.0f) {
    b = -b;
    d = -d;
  }
  if (d > 0.9995f) return glm::normalize(a + s * (b - a));
  float theta = std::acos(std::min(d, 1.0f));
  float sin_theta = std::sin(theta);
  return (std::sin((1.0f - s) * theta) * a + std::sin(s * theta) * b) / sin_theta;
}

glm::vec4 finish(const glm::vec4& v, AnimPath path) {
  if (path != AnimPath::Rotation) return v;
  float len = glm::length(v);
  return len > 0.0f ? v / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

}  // namespace

glm::vec4 AnimChannel::sample(float t) const {
  if (times.empty() || values.empty())
    return path == AnimPath::Rotation ? glm::vec4(0, 0, 0, 1)
           : path == AnimPath::Scale  ? glm::vec4(1.0f)
                                      : glm::vec4(0.0f);
  bool cubic = interpolation == Interpolation::CubicSpline;
  // The value of key k: cubic-spline keys store (in-tangent, value, out-tangent).
  auto value = [&](std::size_t k) { return values[cubic ? 3 * k + 1 : k]; };
  std::size_t last = times.size() - 1;
  if (!(t > times.front())) return finish(value(0), path);  // also catches NaN
  if (t >= times.back()) return finish(value(last), path);

  // times[k] <= t < times[k + 1]
  std::size_t k = std::size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  float dt = times[k + 1] - times[k];
  float s = (t - times[k]) / dt;
  switch (interpolation) {
    case Interpolation::Step:
      return finish(value(k), path);
    case Interpolation::Linear:
      if (path == AnimPath::Rotation) return finish(slerp(value(k), value(k + 1), s), path);
      return value(k) + s * (value(k + 1) - value(k));
    case Interpolation::CubicSpline: {
      // glTF Hermite spline; tangents are per second, so they are scaled by the key interval.
      float s2 = s * s, s3 = s2 * s;
      glm::vec4 out_tangent = values[3 * k + 2];
      glm::vec4 in_tangent = values[3 * (k + 1)];
      glm::vec4 v = (2.0f * s3 - 3.0f * s2 + 1.0f) * value(k) +
                    dt * (s3 - 2.0f * s2 + s) * out_tangent +
                    (-2.0f * s3 + 3.0f * s2) * value(k + 1) + dt * (s3 - s2) * in_tangent;
      return finish(v, path);
    }
  }
  return finish(value(k), path);
}

float Animation::duration() const {
  float d = 0.0f;
  for (const auto& c : channels)
    if (!c.times.empty()) d = std::max(d, c.times.back());
  return d;
}

}  // namespace ddish::scene
