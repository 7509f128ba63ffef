// GGX zonal-harmonic lobe: the integration against an independent brute-force quadrature, the
// project's table against the integration, and the thesis's published fit against both.
#include <cmath>

#include <gtest/gtest.h>

#include "sh/ggx_zh.h"
#include "test_util.h"

namespace ddish::sh {
namespace {

using test::kPi;

double ggx_d(double cos_h, double alpha) {
  if (cos_h <= 0.0) return 0.0;
  const double a2 = alpha * alpha;
  const double d = cos_h * cos_h * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// Normalised zonal moments k_l of a lobe g(theta) over the upper hemisphere (theta = angle from
// the lobe axis), by the midpoint rule in theta.
template <typename Lobe>
BandScales zonal_moments(Lobe g) {
  const int n = 200000;
  double m[5] = {};
  for (int i = 0; i < n; ++i) {
    const double th = (i + 0.5) * (kPi / 2.0) / n;
    const double mu = std::cos(th);
    const double w = std::sin(th) * g(th);
    for (int l = 0; l <= 4; ++l) m[l] += w * test::legendre(l, mu);
  }
  BandScales k{};
  for (int l = 0; l <= 4; ++l) k[std::size_t(l)] = float(m[l] / m[0]);
  return k;
}

// The lobe of ggx_zh.h straight from its definition: g = D(h) max(cos theta, 0) / 4 with
// theta_h = theta / 2 (view along the normal).
BandScales brute_force(double roughness) {
  const double alpha = roughness * roughness;
  return zonal_moments([alpha](double th) { return ggx_d(std::cos(th / 2.0), alpha) * std::cos(th) / 4.0; });
}

TEST(GgxZh, IntegrationMatchesBruteForce) {
  for (double r : {0.15, 0.3, 0.5, 0.75, 1.0}) {
    const BandScales a = ggx_zh_integrate(float(r)), b = brute_force(r);
    for (int l = 0; l <= 4; ++l) EXPECT_NEAR(a[std::size_t(l)], b[std::size_t(l)], 2e-6) << r << " " << l;
  }
}

TEST(GgxZh, EndsAreDeltaAndClampedCosine) {
  const BandScales k0 = ggx_zh_integrate(0.0f), t0 = ggx_zh(0.0f), f0 = ggx_zh_ikkala_fit(0.0f);
  const BandScales k1 = ggx_zh_integrate(1.0f), t1 = ggx_zh(1.0f), f1 = ggx_zh_ikkala_fit(1.0f);
  const double cosine[5] = {1.0, 2.0 / 3.0, 0.25, 0.0, -1.0 / 24.0};
  for (std::size_t l = 0; l <= 4; ++l) {
    EXPECT_EQ(k0[l], 1.0f);
    EXPECT_EQ(t0[l], 1.0f);
    EXPECT_NEAR(f0[l], 1.0, 3e-4);  // the fit overshoots 1 by up to 2.2e-4 at r = 0
    EXPECT_NEAR(k1[l], cosine[l], 1e-6);
    EXPECT_NEAR(t1[l], cosine[l], 1e-6);
    EXPECT_NEAR(f1[l], cosine[l], 5e-4);
    for (float v : {k0[l], t0[l], f0[l], k1[l], t1[l], f1[l]}) EXPECT_TRUE(std::isfinite(v));
  }
  // Nearly-delta lobes are handled too, and out-of-range input is clamped, never NaN.
  for (float r : {1e-4f, 1e-3f, 0.01f, -1.0f, 2.0f, std::nanf("")}) {
    for (float v : ggx_zh(r)) EXPECT_TRUE(std::isfinite(v)) << r;
    for (float v : ggx_zh_integrate(r)) EXPECT_TRUE(std::isfinite(v)) << r;
  }
}

TEST(GgxZh, TableInterpolationErrorAgainstIntegration) {
  double worst[5] = {};
  for (int i = 0; i <= 2000; ++i) {
    const float r = float(i) / 2000.0f;
    const BandScales a = ggx_zh(r), b = ggx_zh_integrate(r);
    for (int l = 1; l <= 4; ++l)
      worst[l] = std::max(worst[l], double(std::fabs(a[std::size_t(l)] - b[std::size_t(l)])));
  }
  std::printf("[sh] GGX ZH table (%d nodes, cubic) vs integration, max |diff| L1..L4: "
              "%.1e %.1e %.1e %.1e\n", kGgxZhNodes, worst[1], worst[2], worst[3], worst[4]);
  for (int l = 1; l <= 4; ++l) EXPECT_LT(worst[l], 1e-5) << l;
}

// The thesis fit against the project's integration, per band, over roughness 0..1.
TEST(GgxZh, IkkalaFitAgainstIntegration) {
  double worst[5] = {};
  float at[5] = {};
  for (int i = 0; i <= 1000; ++i) {
    const float r = float(i) / 1000.0f;
    const BandScales a = ggx_zh_ikkala_fit(r), b = ggx_zh_integrate(r);
    for (int l = 1; l <= 4; ++l) {
      const double d = std::fabs(a[std::size_t(l)] - b[std::size_t(l)]);
      if (d > worst[l]) {
        worst[l] = d;
        at[l] = r;
      }
    }
  }
  std::printf("[sh] GGX ZH Ikkala fit vs integration, max |diff| L1..L4: %.1e (r=%.3f) "
              "%.1e (r=%.3f) %.1e (r=%.3f) %.1e (r=%.3f)\n",
              worst[1], at[1], worst[2], at[2], worst[3], at[3], worst[4], at[4]);
  // The fit is stated to be good to about the fourth decimal.
  for (int l = 1; l <= 4; ++l) EXPECT_LT(worst[l], 5e-4) << l;
}

// Why that lobe: it is the one that reproduces the published fit. Other plausible readings of
// "the GGX lobe" miss it by 0.1 or more somewhere in roughness 0..1.
TEST(GgxZh, IdentifiedLobeIsTheOneThePublishedFitMatches) {
  double ours = 0.0, ndf = 0.0, no_cos = 0.0, smith = 0.0;
  for (double r : {0.3, 0.5, 0.7, 0.9, 1.0}) {
    const double a = r * r;
    const BandScales fit = ggx_zh_ikkala_fit(float(r));
    const BandScales k_ours = brute_force(r);
    const BandScales k_ndf = zonal_moments([a](double th) { return ggx_d(std::cos(th), a); });
    const BandScales k_no_cos = zonal_moments([a](double th) { return ggx_d(std::cos(th / 2.0), a); });
    const BandScales k_smith = zonal_moments([a](double th) {
      const double c = std::cos(th);  // D / 4 times the Smith G1 of the reflected direction
      return ggx_d(std::cos(th / 2.0), a) * 2.0 * c / (c + std::sqrt(a * a + (1.0 - a * a) * c * c));
    });
    for (std::size_t l = 1; l <= 4; ++l) {
      ours = std::max(ours, double(std::fabs(k_ours[l] - fit[l])));
      ndf = std::max(ndf, double(std::fabs(k_ndf[l] - fit[l])));
      no_cos = std::max(no_cos, double(std::fabs(k_no_cos[l] - fit[l])));
      smith = std::max(smith, double(std::fabs(k_smith[l] - fit[l])));
    }
  }
  std::printf("[sh] GGX lobe candidates vs published fit, max |diff|: D(h)(n.l)/4 %.1e, "
              "NDF about R %.2f, D(h)/4 %.2f, D G1 / 4 %.2f\n", ours, ndf, no_cos, smith);
  EXPECT_LT(ours, 3e-4);
  EXPECT_GT(ndf, 0.1);
  EXPECT_GT(no_cos, 0.1);
  EXPECT_GT(smith, 0.1);
}

TEST(GgxZh, SharpensMonotonicallyAsRoughnessDecreases) {
  BandScales prev = ggx_zh_integrate(0.0f), prev_t = ggx_zh(0.0f);
  for (int i = 1; i <= 500; ++i) {
    const float r = float(i) / 500.0f;
    const BandScales k = ggx_zh_integrate(r), t = ggx_zh(r);
    for (std::size_t l = 1; l <= 4; ++l) {
      EXPECT_LE(k[l], prev[l] + 1e-7f) << "r=" << r << " l=" << l;
      EXPECT_LE(t[l], prev_t[l] + 1e-6f) << "r=" << r << " l=" << l;
    }
    // Higher bands are attenuated more: the lobe acts as a low-pass filter.
    for (std::size_t l = 2; l <= 4; ++l) EXPECT_LT(k[l], k[l - 1] + 1e-7f);
    prev = k;
    prev_t = t;
  }
  EXPECT_GT(ggx_zh(0.2f)[2], ggx_zh(0.6f)[2] + 0.3f);  // clearly sharper, not just ordered
}

TEST(GgxZh, SpecularOfConstantIsTheConstant) {
  const glm::vec3 l(0.3f, 0.6f, 0.9f);
  double z[5] = {4.0 * kPi, 0, 0, 0, 0};
  const ShRgb sh = test::zonal_sh(z, glm::vec3(0, 0, 1), l, 2);
  for (float r : {0.0f, 0.4f, 1.0f}) {
    const glm::vec3 s = ggx_specular(sh, glm::normalize(glm::vec3(1, 2, 3)), r);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(s[ch], l[ch], 1e-5f);
  }
}

TEST(GgxZh, TableIsBuiltFromTheIntegration) {
  const GgxZhTable& t = ggx_zh_table();
  for (int j : {0, 7, 16, 32, kGgxZhNodes - 1}) {
    const BandScales k = ggx_zh_integrate(float(j) / float(kGgxZhNodes - 1));
    for (std::size_t l = 0; l <= 4; ++l) EXPECT_EQ(t[std::size_t(j)][l], k[l]);
  }
}

}  // namespace
}  // namespace ddish::sh
