#include "sh/sh_rgb.h"

#include <algorithm>
#include <cmath>

namespace ddish::sh {

ShRgb& ShRgb::operator+=(const ShRgb& o) {
  order = std::max(order, o.order);
  for (int i = 0; i < kMaxCoeffs; ++i) (*this)[i] += o[i];
  return *this;
}

ShRgb& ShRgb::operator-=(const ShRgb& o) {
  order = std::max(order, o.order);
  for (int i = 0; i < kMaxCoeffs; ++i) (*this)[i] -= o[i];
  return *this;
}

ShRgb& ShRgb::operator*=(float s) {
  for (auto& v : c) v *= s;
  return *this;
}

ShRgb& ShRgb::operator*=(const glm::vec3& s) {
  for (auto& v : c) v *= s;
  return *this;
}

void ShRgb::set_order(int sh_order) {
  order = clamp_order(sh_order);
  // Zeroing the dropped bands keeps the "zero past count()" invariant that arithmetic relies on.
  for (int i = count(); i < kMaxCoeffs; ++i) (*this)[i] = glm::vec3(0.0f);
}

ShRgb operator+(ShRgb a, const ShRgb& b) { return a += b; }
ShRgb operator-(ShRgb a, const ShRgb& b) { return a -= b; }
ShRgb operator*(ShRgb a, float s) { return a *= s; }
ShRgb operator*(float s, ShRgb a) { return a *= s; }

ShRgb lerp(const ShRgb& a, const ShRgb& b, float t) {
  ShRgb r;
  r.order = std::max(a.order, b.order);
  for (int i = 0; i < kMaxCoeffs; ++i) r[i] = a[i] + (b[i] - a[i]) * t;
  return r;
}

glm::vec3 eval(const ShRgb& sh, const glm::vec3& dir) {
  float y[kMaxCoeffs];
  eval_basis(dir, sh.order, y);
  glm::vec3 sum(0.0f);
  for (int i = 0; i < sh.count(); ++i) sum += sh[i] * y[i];
  return sum;
}

float max_abs(const ShRgb& sh) {
  float m = 0.0f;
  for (const auto& v : sh.coeffs())
    m = std::max({m, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  return m;
}

bool all_finite(const ShRgb& sh) {
  for (const auto& v : sh.coeffs())
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
  return true;
}

}  // namespace ddish::sh
