// fp16 and shared-exponent packing: exact half conversion, round trips with measured error
// bounds, and overflow / NaN detection (nothing ever packs to Inf or NaN).
#include <bit>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "sh/packing.h"
#include "test_util.h"

namespace ddish::sh {
namespace {

bool half_is_inf_or_nan(std::uint16_t h) { return (h & 0x7c00u) == 0x7c00u; }

TEST(Half, EveryHalfRoundTrips) {
  for (std::uint32_t h = 0; h < 0x10000u; ++h) {
    const auto hh = static_cast<std::uint16_t>(h);
    const float f = half_to_float(hh);
    if ((hh & 0x7fffu) > 0x7c00u) {
      EXPECT_TRUE(std::isnan(f));
      EXPECT_TRUE((float_to_half(f) & 0x7fffu) > 0x7c00u);
    } else {
      EXPECT_EQ(float_to_half(f), hh) << std::hex << h;
    }
  }
}

TEST(Half, KnownValues) {
  EXPECT_EQ(float_to_half(1.0f), 0x3c00);
  EXPECT_EQ(float_to_half(-2.0f), 0xc000);
  EXPECT_EQ(float_to_half(0.0f), 0x0000);
  EXPECT_EQ(float_to_half(-0.0f), 0x8000);
  EXPECT_EQ(float_to_half(65504.0f), 0x7bff);
  EXPECT_EQ(float_to_half(65519.99f), 0x7bff);
  EXPECT_EQ(float_to_half(65520.0f), 0x7c00);  // the tie rounds to even: the next power, Inf
  EXPECT_EQ(float_to_half(1e6f), 0x7c00);
  EXPECT_EQ(float_to_half(-INFINITY), 0xfc00);
  EXPECT_EQ(float_to_half(0x1p-24f), 0x0001);   // smallest subnormal
  EXPECT_EQ(float_to_half(0x1p-25f), 0x0000);   // tie between 0 and 2^-24: even is 0
  EXPECT_EQ(float_to_half(0x1.8p-24f), 0x0002); // tie between 1 and 2 units: even is 2
  EXPECT_EQ(float_to_half(0x1.4p-23f), 0x0002); // 2.5 units: tie, even is 2
  EXPECT_EQ(float_to_half(0x1p-14f), 0x0400);   // smallest normal
  EXPECT_EQ(float_to_half(0x1.ffcp-15f), 0x0400);  // subnormal rounding up into the normals
  EXPECT_EQ(float_to_half(1.0f + 0x1p-11f), 0x3c00);  // tie, even mantissa 0
  EXPECT_EQ(float_to_half(1.0f + 0x1.8p-10f), 0x3c02); // tie between 1 and 2 ulps: even is 2
}

// For random floats over the whole half range the result is a nearest half, and on a tie the
// even one: checked against the neighbouring halves.
TEST(Half, RoundsToNearestEven) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<std::uint32_t> bits(0x2f000000u, 0x477fefffu);  // 1e-10..65519
  for (int k = 0; k < 200000; ++k) {
    const float f = std::bit_cast<float>(bits(rng));
    const std::uint16_t h = float_to_half(f);
    const double d = std::fabs(double(half_to_float(h)) - f);
    if (h > 0) {
      EXPECT_LE(d, std::fabs(double(half_to_float(std::uint16_t(h - 1))) - f)) << f;
    }
    if (h < 0x7bff) {
      const double up = std::fabs(double(half_to_float(std::uint16_t(h + 1))) - f);
      EXPECT_LE(d, up) << f;
      if (d == up) {
        EXPECT_EQ(h & 1u, 0u) << f;
      }
    }
  }
}

ShRgb random_sh(std::mt19937& rng, int order, float scale) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  ShRgb s(order);
  for (int i = 0; i < s.count(); ++i) s[i] = scale * glm::vec3(u(rng), u(rng), u(rng));
  return s;
}

TEST(Packing, SizesAndLayout) {
  EXPECT_EQ(packed_bytes(2), 56);
  EXPECT_EQ(packed_words(1), 13);
  EXPECT_EQ(packed_words(4), 76);
  PackedL2 p;
  ShRgb s(2);
  s[0] = glm::vec3(1.0f, 2.0f, 3.0f);
  s[8] = glm::vec3(-0.5f);
  PackFormat used{};
  EXPECT_EQ(pack_l2(s, 0x5, p, &used), PackStatus::kOk);
  EXPECT_EQ(used, PackFormat::kHalf);
  EXPECT_EQ(p.words[0], 0x3c00);  // c0.r
  EXPECT_EQ(p.words[2], 0x4200);  // c0.b = 3
  EXPECT_EQ(p.words[27], 0x5);    // meta: the flags, fp16 form
  EXPECT_EQ(packed_flags(p.words, 2), 0x5);
  std::uint16_t small[5];
  EXPECT_EQ(pack_half(s, 0, small), PackStatus::kBadSize);
}

TEST(Packing, HalfRoundTripRelativeError) {
  std::mt19937 rng(4);
  double worst = 0.0;
  for (int t = 0; t < 200; ++t) {
    const ShRgb s = random_sh(rng, 4, 1000.0f);
    std::uint16_t w[packed_words(4)];
    ASSERT_EQ(pack_half(s, 0, w), PackStatus::kOk);
    const ShRgb r = unpack(w, 4);
    for (int i = 0; i < s.count(); ++i)
      for (int ch = 0; ch < 3; ++ch) {
        if (std::fabs(s[i][ch]) < 0x1p-14f) continue;  // subnormals: absolute 2^-25
        worst = std::max(worst, double(std::fabs(r[i][ch] - s[i][ch]) / std::fabs(s[i][ch])));
      }
  }
  std::printf("[sh] fp16 round trip: max relative error %.3e (bound 2^-11 = %.3e)\n", worst,
              std::ldexp(1.0, -11));
  EXPECT_LE(worst, std::ldexp(1.0, -11));
}

TEST(Packing, HalfOverflowAndNaNAreReportedNeverWritten) {
  ShRgb s(2);
  s[0] = glm::vec3(1e6f, 1.0f, 1.0f);
  PackedL2 p;
  EXPECT_EQ(pack_half(s, 0, p.words), PackStatus::kOverflow);
  for (std::uint16_t w : p.words) EXPECT_FALSE(half_is_inf_or_nan(w));
  EXPECT_EQ(half_to_float(p.words[0]), 65504.0f);  // saturated
  s[0] = glm::vec3(65505.0f, 1.0f, 1.0f);            // just past the largest half
  EXPECT_EQ(pack_half(s, 0, p.words), PackStatus::kOverflow);
  s[0] = glm::vec3(1.0f, std::nanf(""), 1.0f);
  EXPECT_EQ(pack_half(s, 0, p.words), PackStatus::kNotFinite);
  EXPECT_EQ(p.words[1], 0u);  // NaN written as 0
  s[0] = glm::vec3(1.0f, 1.0f, -INFINITY);
  EXPECT_EQ(pack_half(s, 0, p.words), PackStatus::kNotFinite);
  for (std::uint16_t w : p.words) EXPECT_FALSE(half_is_inf_or_nan(w));
  EXPECT_EQ(pack_l2(s, 0, p), PackStatus::kNotFinite);
  EXPECT_EQ(pack_shared_exp(s, 0, p.words), PackStatus::kNotFinite);
  s[0] = glm::vec3(std::nanf(""));
  EXPECT_EQ(pack_shared_exp(s, 0, p.words), PackStatus::kNotFinite);
  for (float v : {unpack_l2(p)[0].x, unpack_l2(p)[0].y}) EXPECT_TRUE(std::isfinite(v));
}

// Shared-exponent form: every value within max|channel| / 16383 (at least 13 significant bits
// of the channel's largest value), or 2^-17 absolute for channels below 0.125.
TEST(Packing, SharedExponentRoundTripBound) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> lg(-6.0f, 8.5f);
  double worst = 0.0;
  for (int t = 0; t < 500; ++t) {
    ShRgb s = random_sh(rng, t % 5, 1.0f);
    const glm::vec3 scale(std::pow(10.0f, lg(rng)), std::pow(10.0f, lg(rng)), std::pow(10.0f, lg(rng)));
    s *= scale;
    std::uint16_t w[packed_words(4)];
    ASSERT_EQ(pack_shared_exp(s, 3, w), PackStatus::kOk);
    EXPECT_EQ(packed_format(w, s.order), PackFormat::kSharedExp);
    EXPECT_EQ(packed_flags(w, s.order), 3);
    const ShRgb r = unpack(w, s.order);
    for (int ch = 0; ch < 3; ++ch) {
      float m = 0.0f;
      for (int i = 0; i < s.count(); ++i) m = std::max(m, std::fabs(s[i][ch]));
      const double bound = std::max(double(m) / 16383.0, std::ldexp(1.0, -17));
      for (int i = 0; i < s.count(); ++i) {
        const double e = std::fabs(double(r[i][ch]) - s[i][ch]);
        EXPECT_LE(e, bound) << "t=" << t << " i=" << i << " ch=" << ch;
        if (m > 0.125f) worst = std::max(worst, e / m);
      }
    }
  }
  std::printf("[sh] shared-exponent round trip: max error / channel max %.3e (bound %.3e)\n",
              worst, 1.0 / 16383.0);
}

// A probe beside a 1e6-radiance emitter (a small cap of radiance 1e6, and the whole sphere at
// 1e6, L0 = 3.5e6): fp16 overflows, so pack() picks the shared-exponent form, reports success
// and the radiance it reproduces is within 1e-4 of the original.
TEST(Packing, BrightEmitterUsesSharedExponent) {
  for (double cap : {0.3, 3.14159}) {
    double z[5];
    test::cap_factors(std::cos(cap), z);
    const glm::vec3 axis = glm::normalize(glm::vec3(0.2f, 0.9f, -0.1f));
    const ShRgb s = test::zonal_sh(z, axis, glm::vec3(1e6f, 5e5f, 2e5f), 2);
    PackedL2 p;
    PackFormat used{};
    EXPECT_EQ(pack_l2(s, 1, p, &used), PackStatus::kOk);
    EXPECT_EQ(used, PackFormat::kSharedExp);
    EXPECT_EQ(packed_flags(p.words, 2), 1);
    const ShRgb r = unpack_l2(p);
    const glm::vec3 a = eval(s, axis), b = eval(r, axis);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(b[ch], a[ch], 1e-4 * std::fabs(a[ch]));
  }
  // Beyond the form's range (5.4e8) the overflow is reported and the value saturates, finite.
  ShRgb huge(2);
  huge[0] = glm::vec3(1e12f, 1.0f, 1.0f);
  PackedL2 p;
  EXPECT_EQ(pack_l2(huge, 0, p), PackStatus::kOverflow);
  EXPECT_NEAR(unpack_l2(p)[0].x, kSharedExpMax, 1.0f);
}

}  // namespace
}  // namespace ddish::sh
