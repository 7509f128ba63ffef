// Helpers shared by the SH tests: random directions, analytic SH of zonal test functions.
#pragma once

#include <cmath>
#include <random>

#include <glm/glm.hpp>

#include "sh/basis.h"
#include "sh/sh_rgb.h"

namespace ddish::sh::test {

inline constexpr double kPi = 3.14159265358979323846;

inline glm::vec3 uniform_sphere(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 1.0 - 2.0 * u(rng);
  const double phi = 2.0 * kPi * u(rng);
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
}

// Legendre polynomial P_l(x).
inline double legendre(int l, double x) {
  double p0 = 1.0, p1 = x;
  if (l == 0) return p0;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

// SH of a zonal function g(axis . w) from its Funk-Hecke factors
// zonal[l] = 2 pi * integral_{-1}^{1} g(mu) P_l(mu) dmu: f_lm = zonal[l] Y_lm(axis).
inline ShRgb zonal_sh(const double* zonal, const glm::vec3& axis, const glm::vec3& rgb,
                      int order) {
  ShRgb r(order);
  double y[kMaxCoeffs];
  eval_basis(glm::dvec3(axis), order, y);
  for (int i = 0; i < r.count(); ++i) r[i] = rgb * float(zonal[band_of(i)] * y[i]);
  return r;
}

// Funk-Hecke factors of the clamped cosine max(mu, 0) (Ramamoorthi-Hanrahan A_l).
inline void clamped_cosine_factors(double* z) {
  const double a[5] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0, 0.0, -kPi / 24.0};
  for (int l = 0; l < 5; ++l) z[l] = a[l];
}

// Funk-Hecke factors of a cap (1 for mu > cos_theta0, else 0):
// integral_c^1 P_l = (P_{l-1}(c) - P_{l+1}(c)) / (2l+1) for l >= 1, 1 - c for l = 0.
inline void cap_factors(double cos_theta0, double* z) {
  z[0] = 2.0 * kPi * (1.0 - cos_theta0);
  for (int l = 1; l < 5; ++l)
    z[l] = 2.0 * kPi * (legendre(l - 1, cos_theta0) - legendre(l + 1, cos_theta0)) / (2.0 * l + 1.0);
}

// Root of the summed squared coefficient errors over all channels.
inline double coeff_error(const ShRgb& a, const ShRgb& b) {
  double s = 0.0;
  for (int i = 0; i < kMaxCoeffs; ++i) {
    const glm::dvec3 d = glm::dvec3(a[i]) - glm::dvec3(b[i]);
    s += glm::dot(d, d);
  }
  return std::sqrt(s);
}

// Spherical Fibonacci directions, evenly spread, for dense deterministic checks over normals.
inline glm::vec3 fibonacci_dir(int i, int n) {
  const double golden = (1.0 + std::sqrt(5.0)) / 2.0;
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double phi = 2.0 * kPi * (i / golden - std::floor(i / golden));
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
}

}  // namespace ddish::sh::test
