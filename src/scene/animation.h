// glTF node animations: translation, rotation and scale channels with step, linear and
// cubic-spline sampling, evaluated at any time t.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {

enum class AnimPath { Translation, Rotation, Scale };
enum class Interpolation { Step, Linear, CubicSpline };

struct AnimChannel {
  int node = -1;
  AnimPath path = AnimPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // strictly increasing keyframe times
  // Keyframe values as vec4 (xyz for translation/scale, xyzw quaternion for rotation). For
  // cubic-spline sampling there are 3 per key: in-tangent, value, out-tangent (glTF order).
  std::vector<glm::vec4> values;

  // The channel's value at time t (clamped to the first / last key outside the range).
  // Rotations come back normalised.
  glm::vec4 sample(float t) const;
};

struct Animation {
  std::string name;
  std::vector<AnimChannel> channels;
  float duration() const;
};

}  // namespace ddish::scene
