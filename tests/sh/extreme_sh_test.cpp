// Stiff and extreme cases of the SH module (docs/extreme-cases.md): a 1e6-radiance emitter
// beside dim surfaces (finite coefficients, the ringing it causes in L2 irradiance, what the
// deringing windows do to it, the packer's choice), and roughness at and beyond its ends.
// fp16 overflow of a 1e6 L0 and NaN/Inf packing: packing_test.cpp; radiance ringing reduced by
// the windows: window_test.cpp (ShWindow.ReducesRingingOfSmallBrightLight).
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "sh/convolution.h"
#include "sh/ggx_zh.h"
#include "sh/packing.h"
#include "sh/window.h"
#include "test_util.h"

namespace ddish::sh {
namespace {

constexpr float kEmitter = 1e6f;  // radiance of the bright cap
constexpr float kDim = 0.01f;     // radiance of everything else
constexpr double kCap = 0.1;      // cap half-angle, radians

// A 0.1 rad cap of radiance 1e6 around `axis` over a uniform 0.01 background, L2, analytic.
ShRgb emitter_beside_dim(const glm::vec3& axis) {
  double z[5];
  test::cap_factors(std::cos(kCap), z);
  ShRgb s = test::zonal_sh(z, axis, glm::vec3(kEmitter - kDim), 2);
  s[0] += glm::vec3(kDim * float(std::sqrt(4.0 * test::kPi)));
  return s;
}

float min_irradiance(const ShRgb& s, glm::vec3* where = nullptr) {
  float m = std::numeric_limits<float>::max();
  for (int k = 0; k < 4000; ++k) {
    const glm::vec3 d = test::fibonacci_dir(k, 4000);
    const float e = irradiance(s, d).x;
    if (e < m) {
      m = e;
      if (where) *where = d;
    }
  }
  return m;
}

// The power of the cap, Phi = L * 2 pi (1 - cos theta0): what an L2 irradiance rings with.
double cap_power() { return double(kEmitter) * 2.0 * test::kPi * (1.0 - std::cos(kCap)); }

// L2 irradiance of a point-like source of power Phi along the axis, as a function of
// mu = n . axis: Phi (A0 Y0^2 + A1 (3 / 4 pi) mu + A2 (5 / 4 pi) P2(mu)) =
// Phi (0.09375 + 0.5 mu + 0.46875 mu^2), whose minimum -0.0396 Phi lies at mu = -0.533: a
// surface turned away from the emitter is told it receives negative light, 40000 times the
// 0.01 pi it really receives here. The CPU evaluation returns this raw value (it is a linear
// operator); the shader clamps it to 0 (probe_lighting.glsl, extreme_raster_test.cpp).
TEST(ExtremeSh, BrightEmitterBesideDimRingsBoundedlyInIrradiance) {
  const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f));
  const ShRgb s = emitter_beside_dim(axis);
  ASSERT_TRUE(all_finite(s));
  const double phi = cap_power();
  // Facing the emitter: the L2 value for a point source, 1.0625 Phi (truncation overshoots the
  // true Phi by 6 %; the cap is nearly a point), plus pi * 0.01.
  EXPECT_NEAR(irradiance(s, axis).x, 1.0625 * phi + test::kPi * kDim, 0.01 * phi);
  glm::vec3 where(0.0f);
  const float raw = min_irradiance(s, &where);
  std::printf("[extreme] L2 irradiance of a 1e6 cap: min %.4g Phi at n.axis = %.3f\n", raw / phi,
              double(glm::dot(where, axis)));
  EXPECT_LT(raw, -0.038 * phi);
  EXPECT_GT(raw, -0.041 * phi);
  EXPECT_NEAR(glm::dot(where, axis), -0.533f, 0.03f);
  // Deringing does not cure this: the windows taper band 2 but also band 1, which is what
  // cancels band 0 on the far side. Hann(3): Phi (0.2109 + 0.375 mu + 0.1172 mu^2), minimum
  // -0.0469 Phi at mu = -1 (deeper than raw); Lanczos(3): -0.0343 Phi (13 % shallower). Only
  // the shader's clamp guarantees a non-negative result, so that clamp is kept.
  const float hann = min_irradiance(apply_window(s, Window::kHann, 3.0f));
  const float lanczos = min_irradiance(apply_window(s, Window::kLanczos, 3.0f));
  std::printf("[extreme] windowed: Hann(3) %.4g Phi, Lanczos(3) %.4g Phi\n", hann / phi,
              lanczos / phi);
  EXPECT_NEAR(hann / phi, -0.0469, 0.002);
  EXPECT_NEAR(lanczos / phi, -0.0343, 0.002);
  EXPECT_LT(hann, raw);
  EXPECT_GT(lanczos, raw);
}

// The same probe packed: every coefficient fits fp16 here (L0 = 8.9e3, L1 up to 1.5e4), and a
// cap four times wider (L0 ~ 1.4e5) does not: pack() then takes the shared-exponent form, with
// status kOk, and the dim background survives only to max|channel| / 16383 (documented loss).
TEST(ExtremeSh, EmitterPacksInTheFormThatHoldsIt) {
  const glm::vec3 axis(0.0f, 1.0f, 0.0f);
  const ShRgb narrow = emitter_beside_dim(axis);
  ASSERT_LT(max_abs(narrow), kHalfMax);
  PackedL2 p;
  PackFormat used{};
  EXPECT_EQ(pack_l2(narrow, 0, p, &used), PackStatus::kOk);
  EXPECT_EQ(used, PackFormat::kHalf);

  double z[5];
  test::cap_factors(std::cos(4.0 * kCap), z);
  ShRgb wide = test::zonal_sh(z, axis, glm::vec3(kEmitter), 2);
  wide[0] += glm::vec3(kDim * float(std::sqrt(4.0 * test::kPi)));
  ASSERT_GT(max_abs(wide), kHalfMax);
  EXPECT_EQ(pack_half(wide, 0, p.words), PackStatus::kOverflow);
  EXPECT_EQ(pack_l2(wide, 0, p, &used), PackStatus::kOk);
  EXPECT_EQ(used, PackFormat::kSharedExp);
  const ShRgb back = unpack_l2(p);
  ASSERT_TRUE(all_finite(back));
  for (int i = 0; i < 9; ++i)
    EXPECT_NEAR(back[i].x, wide[i].x, max_abs(wide) / 16383.0f) << i;
}

// Roughness exactly 0 and 1, and outside [0, 1] or not finite: the GGX zonal factors stay in
// [-1, 1] and finite (0 is the delta lobe, all ones; 1 the widest, whose band 4 is slightly
// negative, -0.042, like the clamped cosine's), out-of-range values clamp
// to the ends and NaN is treated as 1 (the widest, most harmless lobe). The values at 0 and 1
// themselves against integration: ggx_zh_test.cpp (GgxZh.EndsAreDeltaAndClampedCosine).
TEST(ExtremeSh, RoughnessEndsAndNonFiniteRoughnessGiveFiniteLobes) {
  const BandScales at0 = ggx_zh(0.0f), at1 = ggx_zh(1.0f);
  for (int l = 0; l <= kMaxOrder; ++l) {
    EXPECT_NEAR(at0[std::size_t(l)], 1.0f, 1e-4f) << l;
    EXPECT_GE(at1[std::size_t(l)], -0.05f) << l;
    EXPECT_LE(at1[std::size_t(l)], 1.0f) << l;
  }
  for (float r : {-1.0f, -0.0f, 2.0f, std::numeric_limits<float>::infinity(),
                  std::numeric_limits<float>::quiet_NaN()}) {
    const BandScales k = ggx_zh(r);
    const BandScales& want = (r > 0.5f || std::isnan(r)) ? at1 : at0;
    for (int l = 0; l <= kMaxOrder; ++l) {
      ASSERT_TRUE(std::isfinite(k[std::size_t(l)])) << r;
      EXPECT_EQ(k[std::size_t(l)], want[std::size_t(l)]) << "roughness " << r << " band " << l;
    }
  }
  // Specular of the 1e6 emitter at both ends, looking straight at it and away from it: finite.
  const glm::vec3 axis(0.0f, 0.0f, 1.0f);
  const ShRgb s = emitter_beside_dim(axis);
  for (float r : {0.0f, 1.0f})
    for (const glm::vec3& d : {axis, -axis}) {
      const glm::vec3 v = ggx_specular(s, d, r);
      EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << r;
      EXPECT_LE(std::abs(v.x), 2.0f * eval(s, axis).x) << r;
    }
}

}  // namespace
}  // namespace ddish::sh
