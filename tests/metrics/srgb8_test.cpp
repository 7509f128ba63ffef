// The 8-bit sRGB tables (metrics/color.h) against the transfer function they replace.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "metrics/color.h"

namespace ddish::metrics {
namespace {

int reference_code(float v) {
  const float c = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
  return static_cast<int>(std::lround(255.0 * double(srgb_encode(c))));
}

TEST(Srgb8, DecodeIsTheTransferFunctionAndEncodeItsExactInverse) {
  for (int c = 0; c < 256; ++c) {
    const auto code = static_cast<std::uint8_t>(c);
    EXPECT_FLOAT_EQ(srgb8_decode(code), srgb_decode(float(c) / 255.0f)) << c;
    EXPECT_EQ(srgb8_encode(srgb8_decode(code)), code) << c;
  }
}

TEST(Srgb8, EncodeRoundsLikeThePowerLawAwayFromCodeBoundaries) {
  // 2^20 values over [0, 1]: every one within a code of lround(255 * encode), and differing
  // only where the float rounding of the boundary itself decides (a handful).
  int differ = 0;
  const int n = 1 << 20;
  for (int i = 0; i <= n; ++i) {
    const float v = float(i) / float(n);
    const int got = srgb8_encode(v);
    const int want = reference_code(v);
    ASSERT_LE(std::abs(got - want), 1) << v;
    differ += got != want;
  }
  EXPECT_LE(differ, 8);
}

TEST(Srgb8, ClampsAndSendsNanToBlack) {
  EXPECT_EQ(srgb8_encode(-1.0f), 0);
  EXPECT_EQ(srgb8_encode(0.0f), 0);
  EXPECT_EQ(srgb8_encode(1.0f), 255);
  EXPECT_EQ(srgb8_encode(1e30f), 255);
  EXPECT_EQ(srgb8_encode(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(srgb8_encode(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_NEAR(srgb8_decode(255), 1.0f, 1e-7f);
  EXPECT_EQ(srgb8_decode(0), 0.0f);
}

}  // namespace
}  // namespace ddish::metrics
