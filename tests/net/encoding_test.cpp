// Per-probe encodings of the stream: sizes, round-trip error within each encoding's stated
// bound on radiance-like probes, saturation instead of Inf/NaN, and rejection of invalid codes.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "net/compact_sh.h"
#include "net/probe_encoding.h"
#include "net_test_util.h"
#include "sh/basis.h"

namespace ddish::net {
namespace {

std::vector<glm::vec3> round_trip(Encoding e, int order, const std::vector<glm::vec3>& in,
                                  bool* exact = nullptr) {
  std::vector<std::uint8_t> bytes(std::size_t(probe_bytes(e, order)));
  const bool ok = encode_probe(e, order, in, bytes);
  if (exact) *exact = ok;
  std::vector<glm::vec3> out(in.size());
  EXPECT_TRUE(decode_probe(e, order, bytes, out));
  return out;
}

TEST(Encoding, BytesPerProbe) {
  EXPECT_EQ(probe_bytes(Encoding::kHalf, 2), 54);
  EXPECT_EQ(probe_bytes(Encoding::kSharedExp, 2), 56);
  EXPECT_EQ(probe_bytes(Encoding::kCompact, 2), 28);
  EXPECT_EQ(probe_bytes(Encoding::kCompact, 1), 15);
  EXPECT_EQ(probe_bytes(Encoding::kCompact, 3), 47);
  EXPECT_EQ(probe_bytes(Encoding::kCompact, 4), 71);
  EXPECT_EQ(probe_bytes(Encoding::kHalf, 4), 150);
  for (int e = 0; e < kEncodingCount; ++e)
    EXPECT_EQ(parse_encoding(encoding_name(Encoding(e))), Encoding(e));
  EXPECT_FALSE(parse_encoding("fp8").has_value());
}

// fp16: relative error <= 2^-11 (round to nearest) for normal halves.
TEST(Encoding, HalfRoundTripWithinHalfUlp) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const int order = 1 + trial % 4;
    const auto in = test::coefficients_of(test::radiance_probe(rng, order, 0.5f + float(trial)));
    const auto out = round_trip(Encoding::kHalf, order, in);
    for (std::size_t j = 0; j < in.size(); ++j)
      for (int c = 0; c < 3; ++c)
        EXPECT_LE(std::fabs(out[j][c] - in[j][c]), std::fabs(in[j][c]) * 0x1p-11f + 0x1p-25f);
  }
}

// Shared exponent: error <= max|channel| / 16383 (sh/packing.h), also past fp16's range.
TEST(Encoding, SharedExponentRoundTripWithinStatedBound) {
  std::mt19937_64 rng(4);
  for (int trial = 0; trial < 2000; ++trial) {
    const int order = 1 + trial % 4;
    const float brightness = std::pow(10.0f, float(trial % 12) - 4.0f);  // 1e-4 .. 1e7
    const auto in = test::coefficients_of(test::radiance_probe(rng, order, brightness));
    const auto out = round_trip(Encoding::kSharedExp, order, in);
    for (int c = 0; c < 3; ++c) {
      float largest = 0.0f;
      for (const glm::vec3& v : in) largest = std::max(largest, std::fabs(v[c]));
      for (std::size_t j = 0; j < in.size(); ++j)
        EXPECT_LE(std::fabs(out[j][c] - in[j][c]), largest / 16383.0f + 0x1p-17f);
    }
  }
}

// Compact: L0 within half its step (<= 2^-12 of the brightest channel), band l within
// 0.5 / qmax_l × 2^-k × sqrt(2l+1) × c_00 of its channel (compact_sh.h), from 1e-6 to 1e9.
TEST(Encoding, CompactRoundTripWithinStatedBound) {
  std::mt19937_64 rng(5);
  double worst_l1 = 0.0, worst_l2 = 0.0;  // error relative to the channel's c_00
  for (int trial = 0; trial < 4000; ++trial) {
    const int order = 1 + trial % 4;
    const float brightness = std::pow(10.0f, float(trial % 16) - 6.0f);
    const auto in =
        test::coefficients_of(test::radiance_probe(rng, order, brightness, 1 + trial % 5));
    bool exact = false;
    const auto out = round_trip(Encoding::kCompact, order, in, &exact);
    EXPECT_TRUE(exact);
    const float brightest = std::max({in[0].x, in[0].y, in[0].z});
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(std::fabs(out[0][c] - in[0][c]), brightest * 0x1p-12f);
      for (std::size_t j = 1; j < in.size(); ++j) {
        const int l = sh::band_of(int(j));
        const float qmax = l == 1 ? 127.0f : 63.0f;
        const float bound = 0.5f / qmax * std::sqrt(float(2 * l + 1)) * out[0][c];
        const float err = std::fabs(out[j][c] - in[j][c]);
        EXPECT_LE(err, bound * 1.0001f + brightest * 1e-6f) << "trial " << trial << " j " << j;
        if (in[0][c] > 0.0f) {
          (l == 1 ? worst_l1 : worst_l2) = std::max(l == 1 ? worst_l1 : worst_l2,
                                                    double(err / in[0][c]));
        }
      }
    }
  }
  // The stated worst cases: 0.68% (l = 1) and 1.77% (l >= 2) of c_00 with the widest range.
  EXPECT_LE(worst_l1, 0.0069);
  EXPECT_LE(worst_l2, 0.0178);
}

// A smooth probe (small high bands) gets a finer range: error well under the widest range's.
TEST(Encoding, CompactRangeRefinesSmoothProbes) {
  std::vector<glm::vec3> in(9, glm::vec3(0.0f));
  in[0] = glm::vec3(2.0f, 1.0f, 0.5f);
  for (std::size_t j = 1; j < 9; ++j) in[j] = 0.05f * in[0] * float(j % 3 + 1) / 3.0f;
  const auto out = round_trip(Encoding::kCompact, 2, in);
  for (std::size_t j = 4; j < 9; ++j)  // l = 2: ratio <= 0.05 / sqrt(5): range k = 3, step / 8
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(std::fabs(out[j][c] - in[j][c]), 0.5f / 63.0f / 8.0f * std::sqrt(5.0f) * in[0][c] * 1.001f);
}

TEST(Encoding, NothingEncodesToInfOrNaN) {
  std::vector<glm::vec3> in(9, glm::vec3(1.0f));
  in[0] = glm::vec3(1e12f, NAN, -5.0f);
  in[3] = glm::vec3(INFINITY, -INFINITY, NAN);
  for (int e = 0; e < kEncodingCount; ++e) {
    bool exact = true;
    const auto out = round_trip(Encoding(e), 2, in, &exact);
    EXPECT_FALSE(exact) << encoding_name(Encoding(e));
    for (const glm::vec3& v : out)
      for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(v[c])) << encoding_name(Encoding(e));
  }
}

TEST(Encoding, CompactClampsBeyondTheRadianceBound) {
  std::vector<glm::vec3> in(4, glm::vec3(0.0f));
  in[0] = glm::vec3(1.0f);
  in[1] = glm::vec3(10.0f);  // > sqrt(3): not the SH of a non-negative function
  bool exact = true;
  const auto out = round_trip(Encoding::kCompact, 1, in, &exact);
  EXPECT_FALSE(exact);
  EXPECT_NEAR(out[1].x, std::sqrt(3.0f), 1e-3f);
}

TEST(Encoding, InvalidCodesAreRejected) {
  std::vector<glm::vec3> out(9);
  // fp16: an Inf and a NaN half.
  std::vector<std::uint8_t> half(54, 0);
  half[10] = 0x00, half[11] = 0x7c;
  EXPECT_FALSE(decode_probe(Encoding::kHalf, 2, half, out));
  half[11] = 0x7e;
  EXPECT_FALSE(decode_probe(Encoding::kHalf, 2, half, out));
  // Shared exponent: meta word without its form bit, or with flag bits.
  std::vector<std::uint8_t> shared(56, 0);
  EXPECT_FALSE(decode_probe(Encoding::kSharedExp, 2, shared, out));
  shared[54] = 0x08;
  EXPECT_TRUE(decode_probe(Encoding::kSharedExp, 2, shared, out));
  shared[54] = 0x09;
  EXPECT_FALSE(decode_probe(Encoding::kSharedExp, 2, shared, out));
  // Compact: padding bits (223 bits used of 224) and q = -2^(b-1).
  std::vector<std::uint8_t> compact(28, 0);
  EXPECT_TRUE(decode_probe(Encoding::kCompact, 2, compact, out));
  compact[27] = 0x80;
  EXPECT_FALSE(decode_probe(Encoding::kCompact, 2, compact, out));
  compact[27] = 0;
  // Bits 42-43 hold L1's range, bits 44..51 its first coefficient: q = -128 is bit 51 alone.
  compact[6] = 0x08;
  EXPECT_FALSE(decode_probe(Encoding::kCompact, 2, compact, out));
}

}  // namespace
}  // namespace ddish::net
