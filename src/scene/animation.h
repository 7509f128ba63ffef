// glTF animations: node translation, rotation and scale channels and morph-target weight
// channels, with step, linear and cubic-spline sampling, evaluated at any time t.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {

enum class AnimPath { Translation, Rotation, Scale, Weights };
enum class Interpolation { Step, Linear, CubicSpline };

struct AnimChannel {
  int node = -1;
  AnimPath path = AnimPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // strictly increasing keyframe times
  // Keyframe values, `width` floats each: 3 for translation and scale, 4 for a rotation
  // quaternion (xyzw), one per morph target for weights. For cubic-spline sampling there are 3
  // values per key: in-tangent, value, out-tangent (glTF order).
  int width = 3;
  std::vector<float> values;

  // Writes the channel's value at time t into out[0, width) (clamped to the first / last key
  // outside the range). Rotations come back normalised; weights are interpolated linearly
  // under LINEAR, as glTF specifies for them.
  void sample(float t, std::span<float> out) const;
  // The same for channels of at most 4 values, the rest 0.
  glm::vec4 sample(float t) const;
};

struct Animation {
  std::string name;
  std::vector<AnimChannel> channels;
  float duration() const;
};

}  // namespace ddish::scene
