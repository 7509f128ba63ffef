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

glm::vec4 as_vec4(const float* v) { return {v[0], v[1], v[2], v[3]}; }

}  // namespace

void AnimChannel::sample(float t, std::span<float> out) const {
  const auto w = std::size_t(width);
  const bool rotation = path == AnimPath::Rotation;
  const bool cubic = interpolation == Interpolation::CubicSpline;
  const std::size_t per_key = cubic ? 3 : 1;
  if (times.empty() || w == 0 || out.size() < w || values.size() < times.size() * per_key * w) {
    // No keys: the neutral value (the identity rotation, unit scale, zero otherwise).
    std::fill(out.begin(), out.end(), path == AnimPath::Scale ? 1.0f : 0.0f);
    if (rotation && out.size() >= 4) out[3] = 1.0f;
    return;
  }
  // Key k's value: cubic-spline keys store (in-tangent, value, out-tangent).
  auto value = [&](std::size_t k) { return values.data() + (cubic ? 3 * k + 1 : k) * w; };
  auto finish = [&]() {
    if (!rotation || w != 4) return;
    const glm::vec4 q = as_vec4(out.data());
    const float len = glm::length(q);
    const glm::vec4 n = len > 0.0f ? q / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    for (int i = 0; i < 4; ++i) out[std::size_t(i)] = n[i];
  };
  auto copy = [&](const float* v) {
    std::copy(v, v + w, out.begin());
    finish();
  };
  const std::size_t last = times.size() - 1;
  if (!(t > times.front())) return copy(value(0));  // also catches NaN
  if (t >= times.back()) return copy(value(last));

  // times[k] <= t < times[k + 1]
  std::size_t k = std::size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const float dt = times[k + 1] - times[k];
  const float s = (t - times[k]) / dt;
  const float* a = value(k);
  const float* b = value(k + 1);
  switch (interpolation) {
    case Interpolation::Step:
      return copy(a);
    case Interpolation::Linear:
      if (rotation && w == 4) {
        const glm::vec4 q = slerp(as_vec4(a), as_vec4(b), s);
        for (int i = 0; i < 4; ++i) out[std::size_t(i)] = q[i];
        return finish();
      }
      for (std::size_t i = 0; i < w; ++i) out[i] = a[i] + s * (b[i] - a[i]);
      return;
    case Interpolation::CubicSpline: {
      // glTF Hermite spline; tangents are per second, so they are scaled by the key interval.
      const float s2 = s * s, s3 = s2 * s;
      const float* out_tangent = values.data() + (3 * k + 2) * w;
      const float* in_tangent = values.data() + 3 * (k + 1) * w;
      for (std::size_t i = 0; i < w; ++i)
        out[i] = (2.0f * s3 - 3.0f * s2 + 1.0f) * a[i] + dt * (s3 - 2.0f * s2 + s) * out_tangent[i] +
                 (-2.0f * s3 + 3.0f * s2) * b[i] + dt * (s3 - s2) * in_tangent[i];
      return finish();
    }
  }
  copy(a);
}

glm::vec4 AnimChannel::sample(float t) const {
  float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  sample(t, std::span<float>(v, std::size_t(std::clamp(width, 0, 4))));
  return as_vec4(v);
}

float Animation::duration() const {
  float d = 0.0f;
  for (const auto& c : channels)
    if (!c.times.empty()) d = std::max(d, c.times.back());
  return d;
}

}  // namespace ddish::scene
