#include "sh/ggx_zh.h"

#include <algorithm>
#include <cmath>

#include "sh/quadrature.h"

namespace ddish::sh {
namespace {

float clamp01(float r) { return std::isfinite(r) ? std::clamp(r, 0.0f, 1.0f) : 1.0f; }

}  // namespace

BandScales ggx_zh_integrate(float roughness) {
  const double r = clamp01(roughness);
  const double a = r * r;
  const double a2 = a * a;
  BandScales k{1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
  // Below this alpha the lobe is narrower than float precision can tell from a delta.
  if (a < 1e-7) return k;

  // With t = tan(theta_h) and v = n, the GGX half-vector measure D(h)(n.h) dw_h equals
  // 2 t a^2 / (a^2 + t^2)^2 dt (times dphi / 2pi), and the Jacobian of the reflection,
  // dw_l = 4 (l.h) dw_h, cancels the 1/4 of the lobe. So with mu = n.l = cos(2 theta_h)
  // = (1 - t^2) / (1 + t^2), the lobe's moments are integrals over t in [0, 1] (mu >= 0) of
  //   2 t a^2 / (a^2 + t^2)^2 * mu * P_l(mu).
  static const GaussLegendre gl = gauss_legendre(16);
  double m[kMaxOrder + 1] = {};
  double lo = 0.0;
  double hi = std::min(1.0, a / 8.0);
  while (lo < 1.0) {
    const double half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
    for (std::size_t q = 0; q < gl.x.size(); ++q) {
      const double t = mid + half * gl.x[q];
      const double t2 = t * t;
      const double d = a2 + t2;
      const double mu = (1.0 - t2) / (1.0 + t2);
      const double w = gl.w[q] * half * 2.0 * t * a2 / (d * d) * mu;
      // Legendre P_0..P_4 by the three-term recurrence.
      double p0 = 1.0, p1 = mu;
      m[0] += w;
      m[1] += w * p1;
      for (int l = 2; l <= kMaxOrder; ++l) {
        const double p2 = ((2.0 * l - 1.0) * mu * p1 - (l - 1.0) * p0) / l;
        m[l] += w * p2;
        p0 = p1;
        p1 = p2;
      }
    }
    lo = hi;
    hi = std::min(1.0, hi * 2.0);
  }
  for (int l = 1; l <= kMaxOrder; ++l) k[static_cast<std::size_t>(l)] = float(m[l] / m[0]);
  return k;
}

const GgxZhTable& ggx_zh_table() {
  // Built once (a few thousand integrand evaluations); function-local statics are thread-safe.
  static const GgxZhTable table = [] {
    GgxZhTable t{};
    for (int j = 0; j < kGgxZhNodes; ++j)
      t[static_cast<std::size_t>(j)] = ggx_zh_integrate(float(j) / float(kGgxZhNodes - 1));
    return t;
  }();
  return table;
}

BandScales ggx_zh(float roughness) {
  const GgxZhTable& t = ggx_zh_table();
  const double x = double(clamp01(roughness)) * (kGgxZhNodes - 1);
  // The 4 nodes around x, shifted inwards at the ends of the table.
  int j0 = int(std::floor(x)) - 1;
  j0 = std::clamp(j0, 0, kGgxZhNodes - 4);
  double w[4];
  for (int a = 0; a < 4; ++a) {
    double p = 1.0;
    for (int b = 0; b < 4; ++b)
      if (b != a) p *= (x - (j0 + b)) / double(a - b);
    w[a] = p;
  }
  BandScales k{1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int l = 1; l <= kMaxOrder; ++l) {
    double v = 0.0;
    for (int a = 0; a < 4; ++a)
      v += w[a] * t[static_cast<std::size_t>(j0 + a)][static_cast<std::size_t>(l)];
    // The exact coefficients never exceed 1; interpolation must not push a flat end above it.
    k[static_cast<std::size_t>(l)] = float(std::min(v, 1.0));
  }
  return k;
}

BandScales ggx_zh_ikkala_fit(float roughness) {
  const double r = clamp01(roughness);
  // Per band l = 1..4: {a, b, c, d, b', c', d', e, f, g} of the published fit.
  static constexpr double kFit[4][10] = {
      {0.27793123, 0.905501229, 2.49220829, 2.88755638, 1.98743320, 1.79537159, 0.636261278,
       0.329615862, 1.54054310, -4.73179141e-04},
      {0.59372022, 10.57518269, 3.49132073, 0.56672964, 9.52855312, 3.58608449, 3.60689811,
       0.29109984, 4.35171889, -3.58678416},
      {0.2400839, 21.6480923, 3.92510137, 0.50116945, 19.90690569, 4.01505002, 3.55551139,
       0.25094573, 7.58146856, -6.47567145},
      {0.000250700498, 5.53340572, 3.98902127, 0.705097221, 3.23348085, 4.63841986,
       3.25144230, 0.211655471, 9.84410536, -8.76804538},
  };
  BandScales k{1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int l = 1; l <= kMaxOrder; ++l) {
    const double* c = kFit[l - 1];
    const double v = c[0] + c[1] * std::cos(c[2] * r + c[3]) + c[4] * std::cos(c[5] * r + c[6]) +
                     r * (c[8] / std::sqrt(c[7] + r * r) + c[9]);
    k[static_cast<std::size_t>(l)] = float(v);
  }
  return k;
}

glm::vec3 ggx_specular(const ShRgb& radiance, const glm::vec3& reflect_dir, float roughness) {
  return eval_convolved(radiance, reflect_dir, ggx_zh(roughness));
}

}  // namespace ddish::sh
