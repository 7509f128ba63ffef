// Cosine convolution (irradiance) of known environments against closed forms.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "sh/convolution.h"
#include "sh/projection.h"
#include "sh/quadrature.h"
#include "test_util.h"

namespace ddish::sh {
namespace {

using test::kPi;

TEST(ShIrradiance, CosineLobeConstants) {
  // The band scales equal 2 pi * integral_0^1 mu P_l(mu) dmu, checked by quadrature here.
  const GaussLegendre gl = gauss_legendre(8);
  for (int l = 0; l <= 4; ++l) {
    double s = 0.0;
    for (std::size_t q = 0; q < gl.x.size(); ++q) {
      const double mu = 0.5 * (gl.x[q] + 1.0);
      s += 0.5 * gl.w[q] * mu * test::legendre(l, mu);
    }
    EXPECT_NEAR(kCosineLobe[std::size_t(l)], 2.0 * kPi * s, 1e-6) << l;
  }
  // Band scales from zonal coefficients: h_l = A_l / sqrt(4 pi / (2l+1)) maps back to A_l.
  BandScales h{};
  for (int l = 0; l <= 4; ++l)
    h[std::size_t(l)] = float(kCosineLobe[std::size_t(l)] / std::sqrt(4.0 * kPi / (2 * l + 1)));
  const BandScales a = band_scales_from_zonal(h);
  for (int l = 0; l <= 4; ++l) EXPECT_NEAR(a[std::size_t(l)], kCosineLobe[std::size_t(l)], 1e-6);
}

TEST(ShIrradiance, ConstantEnvironmentGivesPiL) {
  const glm::vec3 l(0.7f, 1.3f, 2.0f);
  double z[5] = {4.0 * kPi, 0, 0, 0, 0};
  for (int order = 0; order <= 4; ++order) {
    const ShRgb sh = test::zonal_sh(z, glm::vec3(0, 0, 1), l, order);
    for (int k = 0; k < 50; ++k) {
      const glm::vec3 e = irradiance(sh, test::fibonacci_dir(k, 50));
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(e[ch], kPi * l[ch], 1e-5 * kPi * l[ch]);
    }
  }
}

// Sky of radiance S above the horizon (+Y up), ground of radiance G below. The irradiance on a
// surface whose normal has elevation sine s = n.y is pi (S (1 + s) / 2 + G (1 - s) / 2). That is
// linear in s, so it lies in bands 0-1: the L2 approximation is exact here, up to rounding (the
// step's even bands > 0 vanish and the cosine's odd bands > 1 vanish, so no product survives).
TEST(ShIrradiance, SkyAboveGroundBelowMatchesClosedForm) {
  const glm::vec3 sky(1.0f, 1.4f, 2.2f), ground(0.30f, 0.25f, 0.20f);
  auto env = [&](const glm::vec3& w) { return w.y > 0.0f ? sky : ground; };
  auto exact = [&](const glm::vec3& n) {
    return float(kPi) * (sky * (1.0f + n.y) * 0.5f + ground * (1.0f - n.y) * 0.5f);
  };
  // Exact projection: Gauss-Legendre in y on each hemisphere separately (the integrand is a
  // polynomial on each) times a uniform grid in the azimuth about +Y.
  const GaussLegendre gl = gauss_legendre(8);
  ShProjector exact_proj(4);
  const int nphi = 32;
  for (int half = 0; half < 2; ++half) {
    for (std::size_t q = 0; q < gl.x.size(); ++q) {
      const double y = half ? 0.5 * (gl.x[q] + 1.0) : 0.5 * (gl.x[q] - 1.0);
      const double r = std::sqrt(1.0 - y * y);
      for (int p = 0; p < nphi; ++p) {
        const double phi = 2.0 * kPi * (p + 0.5) / nphi;
        const glm::vec3 w(float(r * std::cos(phi)), float(y), float(r * std::sin(phi)));
        exact_proj.add(w, env(w), float(0.5 * gl.w[q] * 2.0 * kPi / nphi));
      }
    }
  }
  for (int order : {1, 2, 4}) {
    ShRgb sh = exact_proj.result();
    sh.set_order(order);
    double worst = 0.0;
    for (int k = 0; k < 400; ++k) {
      const glm::vec3 n = test::fibonacci_dir(k, 400);
      const glm::vec3 e = irradiance(sh, n), x = exact(n);
      for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, double(std::fabs(e[ch] - x[ch]) / x[ch]));
    }
    std::printf("[sh] sky/ground irradiance, L%d from exact projection: max rel. error %.2e\n",
                order, worst);
    EXPECT_LT(worst, 2e-5) << order;
  }
  // And from a Monte-Carlo projection (65536 uniform samples): within MC noise.
  std::mt19937_64 rng(5);
  ShProjector mc(2);
  const int n = 65536;
  for (int k = 0; k < n; ++k) {
    const glm::vec3 w = test::uniform_sphere(rng);
    mc.add(w, env(w), uniform_sphere_weight(n));
  }
  double worst = 0.0;
  for (int k = 0; k < 400; ++k) {
    const glm::vec3 nn = test::fibonacci_dir(k, 400);
    const glm::vec3 e = irradiance(mc.result(), nn), x = exact(nn);
    for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, double(std::fabs(e[ch] - x[ch]) / x[ch]));
  }
  std::printf("[sh] sky/ground irradiance, L2 from 65536 MC samples: max rel. error %.2e\n", worst);
  EXPECT_LT(worst, 0.03);
}

// The worst case for low-order irradiance: a point light (a delta in direction a, power P),
// exact irradiance P max(n.a, 0). The L2 reconstruction of the clamped cosine is
// 1/4 + mu/2 + 5/32 (3 mu^2 - 1): its largest error is 3/32 = 9.4 % of the peak, at the
// terminator (mu = 0), and its RMS error over all normals is 3.6 % of the peak. Band 4
// (A_4 = -pi/24) lowers both.
TEST(ShIrradiance, PointLightErrorIsTheKnownL2Level) {
  const glm::vec3 a = glm::normalize(glm::vec3(0.4f, 0.9f, 0.1f));
  for (int order : {2, 4}) {
    const ShRgb sh = project_direction(a, glm::vec3(1.0f), order);
    double worst = 0.0, rms = 0.0;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
      const glm::vec3 nn = test::fibonacci_dir(k, n);
      const double err = irradiance(sh, nn).x - std::max(0.0f, glm::dot(nn, a));
      worst = std::max(worst, std::fabs(err));
      rms += err * err;
    }
    rms = std::sqrt(rms / n);
    std::printf("[sh] point-light irradiance, L%d: max error %.4f, RMS %.4f (of the peak)\n", order,
                worst, rms);
    if (order == 2) {
      EXPECT_NEAR(worst, 3.0 / 32.0, 2e-3);
      EXPECT_LT(rms, 0.04);
    } else {
      EXPECT_LT(worst, 3.0 / 32.0);  // band 4 (A_4 = -pi/24) improves it
    }
  }
}

TEST(ShIrradiance, ConvolveMatchesDirectEvaluation) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  ShRgb f(4);
  for (int i = 0; i < f.count(); ++i) f[i] = glm::vec3(u(rng), u(rng), u(rng));
  const ShRgb e = irradiance_sh(f);
  for (int k = 0; k < 20; ++k) {
    const glm::vec3 nn = test::fibonacci_dir(k, 20);
    const glm::vec3 a = eval(e, nn), b = irradiance(f, nn);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a[ch], b[ch], 1e-5f);
  }
  // Convolution with a zonal kernel given as zonal coefficients: a delta kernel (h_l =
  // sqrt((2l+1)/4pi)) is the identity.
  BandScales delta{};
  for (int l = 0; l <= 4; ++l) delta[std::size_t(l)] = float(std::sqrt((2 * l + 1) / (4 * kPi)));
  const ShRgb same = convolve_zonal(f, delta);
  for (int i = 0; i < f.count(); ++i)
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(same[i][ch], f[i][ch], 1e-6f);
}

}  // namespace
}  // namespace ddish::sh
