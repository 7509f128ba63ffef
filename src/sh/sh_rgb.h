// RGB spherical-harmonic coefficients of one function (radiance, irradiance) on the sphere, for
// an order chosen at run time (1..4 in ddish; 0 is allowed). Storage is fixed at the L4 size so
// the type is trivially copyable and can live in plain arrays; coefficients past the order are
// kept at zero, so arithmetic on the whole array is always valid.
#pragma once

#include <array>
#include <span>

#include <glm/vec3.hpp>

#include "sh/basis.h"

namespace ddish::sh {

struct ShRgb {
  std::array<glm::vec3, kMaxCoeffs> c{};  // c[i] = RGB coefficient of Y_i; zero past count()
  int order = 2;

  ShRgb() = default;
  explicit ShRgb(int sh_order) : order(clamp_order(sh_order)) {}

  int count() const { return coeff_count(order); }
  glm::vec3& operator[](int i) { return c[static_cast<std::size_t>(i)]; }
  const glm::vec3& operator[](int i) const { return c[static_cast<std::size_t>(i)]; }
  std::span<glm::vec3> coeffs() { return {c.data(), static_cast<std::size_t>(count())}; }
  std::span<const glm::vec3> coeffs() const {
    return {c.data(), static_cast<std::size_t>(count())};
  }

  ShRgb& operator+=(const ShRgb& o);
  ShRgb& operator-=(const ShRgb& o);
  ShRgb& operator*=(float s);
  ShRgb& operator*=(const glm::vec3& s);  // per-channel scale (a colour filter)

  // Changes the order, dropping the bands above a lower order or zero-filling new ones.
  void set_order(int sh_order);

  static int clamp_order(int sh_order) {
    return sh_order < 0 ? 0 : (sh_order > kMaxOrder ? kMaxOrder : sh_order);
  }
};

// The result's order is the larger of the two; missing bands count as zero.
ShRgb operator+(ShRgb a, const ShRgb& b);
ShRgb operator-(ShRgb a, const ShRgb& b);
ShRgb operator*(ShRgb a, float s);
ShRgb operator*(float s, ShRgb a);

// (1 - t) * a + t * b: the running-average blend of the probe volume (t = 1/k, then 1 - hysteresis).
ShRgb lerp(const ShRgb& a, const ShRgb& b, float t);

// The function the coefficients represent, at the unit direction dir.
glm::vec3 eval(const ShRgb& sh, const glm::vec3& dir);

// Largest |coefficient component| (used to pick the packed form) and whether all are finite.
float max_abs(const ShRgb& sh);
bool all_finite(const ShRgb& sh);

}  // namespace ddish::sh
