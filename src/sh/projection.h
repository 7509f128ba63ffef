// Monte-Carlo projection of a function on the sphere onto SH: an accumulator of
// sum_k f(w_k) * Y_i(w_k) * weight_k. With weight = 1 / pdf(w_k) / N the sum is an unbiased
// estimate of the coefficient integral f_i = integral of f(w) Y_i(w) over the sphere; for
// uniform directions on the sphere that weight is 4*pi / N (uniform_sphere_weight).
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "sh/sh_rgb.h"

namespace ddish::sh {

inline constexpr float kFourPi = 12.566370614359172f;

// Per-sample weight of N directions spread uniformly (random or a lattice) over the sphere.
inline float uniform_sphere_weight(std::uint64_t n) { return n ? kFourPi / float(n) : 0.0f; }

class ShProjector {
 public:
  explicit ShProjector(int order = 2) : order_(ShRgb::clamp_order(order)) {}

  // Adds f(dir) * Y_i(dir) * weight; dir must be unit length.
  void add(const glm::vec3& dir, const glm::vec3& value, float weight);
  // Folds another accumulator of the same order in (parallel reduction; order is the larger).
  void merge(const ShProjector& other);
  void reset();

  // The accumulated sums as coefficients (the estimate when weights are 1/(pdf N)).
  ShRgb result() const;
  // The self-normalised estimate 4*pi * sum / sum(weights): exact for constants whatever the
  // weights' scale, at the cost of a small bias; useful when only relative weights are known.
  ShRgb result_normalized() const;

  int order() const { return order_; }
  std::uint64_t sample_count() const { return n_; }
  double weight_sum() const { return weight_sum_; }

 private:
  // Double sums: a million fp32 additions would lose ~3 digits to rounding.
  std::array<glm::dvec3, kMaxCoeffs> sum_{};
  double weight_sum_ = 0.0;
  std::uint64_t n_ = 0;
  int order_;
};

// One-shot helper: the coefficients of a single sample (value * weight * Y_i(dir)), e.g. a
// delta light or a directional light of known power.
ShRgb project_direction(const glm::vec3& dir, const glm::vec3& value, int order);

}  // namespace ddish::sh
