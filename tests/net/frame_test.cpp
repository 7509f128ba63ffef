// Probe frames: round trips of keyframes and deltas (every encoding, with and without zstd, with
// distance moments, a delta's for some of its probes only, and relocation offsets), and every
// rejection kind of the decoder on hand-made bad messages.
#include <bit>
#include <cmath>
#include <limits>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "net/byte_io.h"
#include "net/probe_frame.h"
#include "sh/packing.h"
#include "net_test_util.h"

namespace ddish::net {
namespace {

constexpr int kSampleMoments = 3;  // a 3x3 moment map per probe

ProbeFrame sample_frame(Encoding encoding, bool zstd, FrameKind kind = FrameKind::kDelta,
                        bool visibility = true) {
  ProbeFrame f;
  f.header.kind = kind;
  f.header.encoding = encoding;
  f.header.sh_order = 2;
  f.header.zstd = zstd;
  f.header.counts[0] = 4, f.header.counts[1] = 3, f.header.counts[2] = 2;  // 24 probes
  f.header.scene_id = 0x1234567890abcdefull;
  f.header.stream_id = 0x5eed;
  f.header.frame = 42;
  f.header.base_frame = kind == FrameKind::kDelta ? 41 : 42;
  f.header.server_time_us = 987654321;
  f.header.scene_time = 1.25;
  std::mt19937_64 rng(7);
  f.updated = {0, 1, 2, 7, 8, 20, 23};
  for (std::size_t k = 0; k < f.updated.size(); ++k)
    for (const glm::vec3& v : test::coefficients_of(test::radiance_probe(rng, 2, 1.0f + float(k))))
      f.coefficients.push_back(v);
  if (kind == FrameKind::kDelta) {
    f.deactivated = {3, 21};
    f.deactivated_flags = {kWireFlagInactive, kWireFlagInactive | kWireFlagInsideGeometry};
  }
  if (visibility) {
    f.header.moment_resolution = kSampleMoments;
    f.header.moment_range = 2.5f;
    // A keyframe maps every probe it carries; this delta 3 of its 7 (the others' maps settled).
    f.mapped = kind == FrameKind::kKeyframe ? f.updated : std::vector<std::uint32_t>{1, 7, 23};
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (std::size_t k = 0; k < f.mapped.size() * kSampleMoments * kSampleMoments; ++k) {
      const float m = u(rng);
      f.moments.emplace_back(m, m * m + 0.1f * u(rng) * (1.0f - m * m));  // mean d^2 >= (mean d)^2
    }
    f.moments[3] = glm::vec2(1.0f);  // a texel no ray reached
    f.moments[4] = glm::vec2(0.0f);  // a probe on a surface
    f.relocated = {7, 20};
    f.offsets = {glm::vec3(0.1f, -0.2f, 0.0f), glm::vec3(-1e-3f, 0.0f, 0.3f)};
  }
  return f;
}

TEST(Frame, RoundTripEveryEncodingAndCompression) {
  for (int e = 0; e < kEncodingCount; ++e)
    for (bool zstd : {false, true})
      for (FrameKind kind : {FrameKind::kKeyframe, FrameKind::kDelta}) {
        const ProbeFrame f = sample_frame(Encoding(e), zstd, kind);
        const std::vector<std::uint8_t> bytes = encode_frame(f);
        const DecodeResult r = decode_frame(bytes);
        ASSERT_TRUE(r.ok) << r.detail;
        const FrameHeader& h = r.frame.header;
        EXPECT_EQ(h.kind, kind);
        EXPECT_EQ(h.encoding, Encoding(e));
        EXPECT_EQ(h.zstd, zstd);
        EXPECT_EQ(h.scene_id, f.header.scene_id);
        EXPECT_EQ(h.stream_id, f.header.stream_id);
        EXPECT_EQ(h.frame, f.header.frame);
        EXPECT_EQ(h.base_frame, f.header.base_frame);
        EXPECT_EQ(h.server_time_us, f.header.server_time_us);
        EXPECT_EQ(h.scene_time, f.header.scene_time);
        EXPECT_EQ(h.probe_count(), 24u);
        EXPECT_EQ(r.frame.updated, f.updated);
        EXPECT_EQ(r.frame.mapped, f.mapped);
        EXPECT_EQ(r.frame.deactivated, f.deactivated);
        EXPECT_EQ(r.frame.deactivated_flags, f.deactivated_flags);
        ASSERT_EQ(r.frame.coefficients.size(), f.coefficients.size());
        for (std::size_t j = 0; j < f.coefficients.size(); ++j)  // loosest bound: compact L2
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(r.frame.coefficients[j][c], f.coefficients[j][c],
                        0.0178f * f.coefficients[j - j % 9][c] + 1e-6f);
        // Moments: fp16 rounding of a number in [0, 1], at most 2^-12 (half an ulp below 1).
        EXPECT_EQ(h.moment_resolution, kSampleMoments);
        EXPECT_EQ(h.moment_range, 2.5f);
        ASSERT_EQ(r.frame.moments.size(), f.moments.size());
        for (std::size_t t = 0; t < f.moments.size(); ++t)
          for (int c = 0; c < 2; ++c) {
            EXPECT_NEAR(r.frame.moments[t][c], f.moments[t][c], 0x1p-12f);
            EXPECT_EQ(r.frame.moments[t][c], sh::half_to_float(sh::float_to_half(f.moments[t][c])));
          }
        EXPECT_EQ(r.frame.moments[3], glm::vec2(1.0f));
        EXPECT_EQ(r.frame.moments[4], glm::vec2(0.0f));
        EXPECT_EQ(r.frame.relocated, f.relocated);
        EXPECT_EQ(r.frame.offsets, f.offsets);  // exact: the f32 the rasterizer uploads
        if (!zstd) {  // 100 header + 7 + 2 + 2 + 3 index bytes + 2 flags (delta), or 7 + 2 + 7
                      // (keyframe), + coefficients + maps + offsets
          const std::size_t maps = kind == FrameKind::kDelta ? 3 : 7;
          ASSERT_EQ(f.mapped.size(), maps);
          EXPECT_EQ(bytes.size(), kFrameHeaderBytes + 16u +
                                      7u * std::size_t(probe_bytes(Encoding(e), 2)) + maps * 4 * 9 + 2 * 12);
        }
      }
}

TEST(Frame, EmptyDeltaIsTheHeaderAndIndexGapsAreOneByte) {
  ProbeFrame f = sample_frame(Encoding::kCompact, false, FrameKind::kDelta, false);
  f.updated.clear();
  f.coefficients.clear();
  f.deactivated.clear();
  f.deactivated_flags.clear();
  EXPECT_EQ(encode_frame(f).size(), kFrameHeaderBytes);
  // 200 consecutive probes past index 300: 2 bytes for the first gap, 1 for each other.
  f.header.counts[0] = 1000, f.header.counts[1] = 1, f.header.counts[2] = 1;
  for (std::uint32_t i = 300; i < 500; ++i) f.updated.push_back(i);
  f.coefficients.assign(200 * 9, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(encode_frame(f).size(), kFrameHeaderBytes + 2 + 199 + 200 * 28);
}

// --- rejections -----------------------------------------------------------------------------

std::vector<std::uint8_t> good_message(bool zstd = false) {
  return encode_frame(sample_frame(Encoding::kHalf, zstd));
}

void put32(std::vector<std::uint8_t>& m, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) m[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}
void put64(std::vector<std::uint8_t>& m, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) m[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}

void expect_reject(const std::vector<std::uint8_t>& m, RejectKind kind) {
  const DecodeResult r = decode_frame(m);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.reject, kind) << "got " << reject_name(r.reject) << ": " << r.detail;
  EXPECT_FALSE(r.detail.empty());
}

TEST(FrameReject, Truncated) {
  std::vector<std::uint8_t> m = good_message();
  expect_reject({m.begin(), m.begin() + std::ptrdiff_t(kFrameHeaderBytes - 1)}, RejectKind::kTruncated);
  expect_reject({}, RejectKind::kTruncated);
  for (std::size_t cut = kFrameHeaderBytes; cut < m.size(); cut += 7)
    expect_reject({m.begin(), m.begin() + std::ptrdiff_t(cut)}, RejectKind::kTruncated);
}

TEST(FrameReject, MagicAndVersion) {
  std::vector<std::uint8_t> m = good_message();
  m[0] = 'X';
  expect_reject(m, RejectKind::kBadMagic);
  m = good_message();
  m[4] = 3;
  expect_reject(m, RejectKind::kBadVersion);
  // A version-1 peer's empty delta: 88 bytes, shorter than this version's header, still
  // "bad-version" and not "truncated", so that the client's line says what is wrong.
  m.assign(88, 0);
  std::memcpy(m.data(), kFrameMagic, 4);
  m[4] = 1;
  const DecodeResult r = decode_frame(m);
  EXPECT_EQ(r.reject, RejectKind::kBadVersion);
  EXPECT_EQ(r.detail, "protocol version 1, this build speaks 2");
}

TEST(FrameReject, BadHeaderFields) {
  const auto with = [](std::size_t at, std::uint8_t v) {
    std::vector<std::uint8_t> m = good_message();
    m[at] = v;
    return m;
  };
  expect_reject(with(6, 2), RejectKind::kBadHeader);   // kind
  expect_reject(with(7, 3), RejectKind::kBadHeader);   // encoding
  expect_reject(with(8, 0), RejectKind::kBadHeader);   // order
  expect_reject(with(8, 5), RejectKind::kBadHeader);
  expect_reject(with(9, 2), RejectKind::kBadHeader);   // flags
  expect_reject(with(10, 17), RejectKind::kBadHeader);  // moment resolution beyond 16
  expect_reject(with(11, 1), RejectKind::kBadHeader);   // reserved
  std::vector<std::uint8_t> none = encode_frame(sample_frame(Encoding::kHalf, false, FrameKind::kDelta, false));
  put32(none, 72, std::bit_cast<std::uint32_t>(1.0f));  // a range without moments
  expect_reject(none, RejectKind::kBadHeader);
  for (float range : {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::vector<std::uint8_t> m = good_message();
    put32(m, 72, std::bit_cast<std::uint32_t>(range));
    expect_reject(m, RejectKind::kBadHeader);
  }
  std::vector<std::uint8_t> m = good_message();
  put32(m, 12, 0);  // empty grid
  expect_reject(m, RejectKind::kBadHeader);
  m = good_message();
  put32(m, 12, 1u << 12), put32(m, 16, 1u << 12), put32(m, 20, 2);  // 2^25 probes
  expect_reject(m, RejectKind::kBadHeader);
  m = good_message();
  put64(m, 48, 42);  // a delta whose base is its own frame
  expect_reject(m, RejectKind::kBadHeader);
  m = good_message();
  put64(m, 64, 0x7ff8000000000000ull);  // NaN scene time
  expect_reject(m, RejectKind::kBadHeader);
}

TEST(FrameReject, SizeMismatch) {
  std::vector<std::uint8_t> m = good_message();
  m.push_back(0);  // a byte after the payload
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 76, 25);  // more updated probes than the grid holds
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 76, 6);  // one probe fewer than the payload carries
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 84, 10);  // more relocated probes than updated and deactivated ones
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 84, 1);  // one relocated probe fewer than the payload carries: the lists misalign
  EXPECT_FALSE(decode_frame(m).ok);
  m = good_message();
  m[10] = kSampleMoments + 1;  // moment maps larger than the records
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 88, 8);  // more mapped probes than updated ones
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 88, 4);  // one moment map more than the payload carries
  expect_reject(m, RejectKind::kSizeMismatch);
  m = encode_frame(sample_frame(Encoding::kHalf, false, FrameKind::kDelta, false));
  put32(m, 88, 1);  // a moment map in a stream without moments
  expect_reject(m, RejectKind::kSizeMismatch);
  m = good_message();
  put32(m, 96, 5000);  // uncompressed size unlike the payload's
  expect_reject(m, RejectKind::kSizeMismatch);
  DecodeLimits tight;
  tight.max_payload_bytes = 100;
  const DecodeResult r = decode_frame(good_message(), tight);
  EXPECT_EQ(r.reject, RejectKind::kSizeMismatch);
}

TEST(FrameReject, BadIndices) {
  ProbeFrame f = sample_frame(Encoding::kHalf, false);
  f.updated.back() = 24;  // the grid has 24 probes
  expect_reject(encode_frame(f), RejectKind::kBadIndex);
  f = sample_frame(Encoding::kHalf, false);
  f.deactivated = {2, 21};  // probe 2 is also updated
  expect_reject(encode_frame(f), RejectKind::kBadIndex);
  // A gap that overflows past 2^32 is out of the grid too.
  std::vector<std::uint8_t> m = good_message();
  m[kFrameHeaderBytes + 1] = 0xff, m[kFrameHeaderBytes + 2] = 0x0f;  // not a 1-byte varint now
  const DecodeResult r = decode_frame(m);
  EXPECT_FALSE(r.ok);
}

TEST(FrameReject, BadCoefficients) {
  std::vector<std::uint8_t> m = encode_frame(sample_frame(Encoding::kHalf, false, FrameKind::kDelta, false));
  // The last probe's last half becomes Inf; then NaN.
  m[m.size() - 1] = 0x7c, m[m.size() - 2] = 0x00;
  expect_reject(m, RejectKind::kBadCoefficients);
  m[m.size() - 1] = 0xff, m[m.size() - 2] = 0xff;
  expect_reject(m, RejectKind::kBadCoefficients);
  ProbeFrame f = sample_frame(Encoding::kHalf, false);
  f.deactivated_flags[0] = 0x04;  // not a flag the stream carries
  expect_reject(encode_frame(f), RejectKind::kBadCoefficients);
}

// Moments outside [0, 1] or not numbers, a moment map of a probe that is not updated, a keyframe
// without the maps of all its probes, offsets that are not finite or zero or of a probe that is
// not updated: "bad-visibility", with the probe named.
TEST(FrameReject, BadVisibility) {
  const std::size_t map = 4 * 9;
  // The payload after the index lists and flags (7 + 2 + 2 + 3 index bytes, 2 flag bytes) and
  // the 7 probes' coefficients: the 3 maps.
  const std::size_t first_moment = kFrameHeaderBytes + 16 + 7 * std::size_t(probe_bytes(Encoding::kHalf, 2));
  for (std::uint16_t half : {std::uint16_t(0x3c01), std::uint16_t(0x4000), std::uint16_t(0x8001),
                             std::uint16_t(0x7c00), std::uint16_t(0x7e00)}) {  // >1, 2, <0, Inf, NaN
    for (std::size_t at : {first_moment, first_moment + 2 * 9 + 4, first_moment + 3 * map - 2}) {
      std::vector<std::uint8_t> m = good_message();
      m[at] = std::uint8_t(half), m[at + 1] = std::uint8_t(half >> 8);
      const DecodeResult r = decode_frame(m);
      EXPECT_EQ(r.reject, RejectKind::kBadVisibility) << r.detail;
      EXPECT_NE(r.detail.find("moment texel"), std::string::npos) << r.detail;
    }
  }
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    ProbeFrame f = sample_frame(Encoding::kHalf, false);
    f.offsets[1].y = bad;
    expect_reject(encode_frame(f), RejectKind::kBadVisibility);
  }
  ProbeFrame f = sample_frame(Encoding::kHalf, false);
  f.offsets[0] = glm::vec3(0.0f);  // listed, but not relocated: no encoder writes it
  expect_reject(encode_frame(f), RejectKind::kBadVisibility);
  f = sample_frame(Encoding::kHalf, false);
  f.relocated = {7, 22};  // 22 is neither updated nor deactivated
  const DecodeResult r = decode_frame(encode_frame(f));
  EXPECT_EQ(r.reject, RejectKind::kBadVisibility);
  EXPECT_EQ(r.detail, "probe 22 has an offset but is neither updated nor deactivated");
  f.relocated = {7, 21};  // a deactivated probe's offset: the shader weighs inactive probes too
  EXPECT_TRUE(decode_frame(encode_frame(f)).ok);
  f = sample_frame(Encoding::kHalf, false);
  f.mapped = {1, 3, 23};  // 3 is deactivated: a map travels only with coefficients
  const DecodeResult unmapped = decode_frame(encode_frame(f));
  EXPECT_EQ(unmapped.reject, RejectKind::kBadVisibility);
  EXPECT_EQ(unmapped.detail, "probe 3 has a moment map but is not updated");
  // A keyframe replaces the client's whole state: one without a map of each of its probes
  // would leave a probe with another frame's (or no) visibility.
  f = sample_frame(Encoding::kHalf, false, FrameKind::kKeyframe);
  f.mapped = {0, 1, 2, 7, 8, 20};  // 23's map missing
  f.moments.resize(f.mapped.size() * 9);
  const DecodeResult incomplete = decode_frame(encode_frame(f));
  EXPECT_EQ(incomplete.reject, RejectKind::kBadVisibility);
  EXPECT_EQ(incomplete.detail, "a keyframe with 6 moment maps for its 7 probes");
  f.mapped.clear();
  f.moments.clear();
  EXPECT_EQ(decode_frame(encode_frame(f)).reject, RejectKind::kBadVisibility);
}

TEST(FrameReject, Decompression) {
  std::vector<std::uint8_t> m = good_message(true);
  m[kFrameHeaderBytes + 6] ^= 0xff;  // inside the zstd frame
  const DecodeResult r = decode_frame(m);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.reject == RejectKind::kDecompression || r.reject == RejectKind::kBadIndex ||
              r.reject == RejectKind::kSizeMismatch || r.reject == RejectKind::kBadCoefficients)
      << reject_name(r.reject);
  m = good_message(true);
  m[kFrameHeaderBytes] ^= 0xff;  // zstd magic
  expect_reject(m, RejectKind::kDecompression);
}

TEST(FrameReject, RandomCorruptionNeverCrashes) {
  std::mt19937_64 rng(11);
  int rejected = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::uint8_t> m = good_message(trial % 2 == 0);
    const int flips = 1 + int(rng() % 4);
    for (int k = 0; k < flips; ++k) m[rng() % m.size()] ^= std::uint8_t(1u << (rng() % 8));
    const DecodeResult r = decode_frame(m);
    if (!r.ok) {
      ++rejected;
      continue;
    }
    for (const glm::vec3& v : r.frame.coefficients)
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(v[c]));
    for (const glm::vec2& v : r.frame.moments)
      ASSERT_TRUE(v.x >= 0.0f && v.x <= 1.0f && v.y >= 0.0f && v.y <= 1.0f);
    for (const glm::vec3& o : r.frame.offsets)
      ASSERT_TRUE(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z));
    for (std::uint32_t i : r.frame.updated) ASSERT_LT(i, r.frame.header.probe_count());
  }
  EXPECT_GT(rejected, 1000);
}

// The INFO reply's grid bounds: 24 bytes that round-trip exactly (a flat axis included); a wrong
// length, a non-finite value, a minimum above the maximum or an extent beyond float's range is
// refused and leaves the output alone.
TEST(GridBounds, RoundTripAndRefusals) {
  const scene::Aabb b{glm::vec3(-12.625f, 0.0f, 1e-3f), glm::vec3(11.0f, 0.0f, 1e4f)};
  const std::vector<std::uint8_t> bytes = encode_grid_bounds(b);
  ASSERT_EQ(bytes.size(), kGridBoundsBytes);
  scene::Aabb out;
  ASSERT_TRUE(decode_grid_bounds(bytes, out));
  EXPECT_EQ(out.min, b.min);
  EXPECT_EQ(out.max, b.max);

  const scene::Aabb untouched{glm::vec3(1.0f), glm::vec3(2.0f)};
  const auto refused = [&](std::vector<std::uint8_t> bad) {
    scene::Aabb o = untouched;
    const bool ok = decode_grid_bounds(bad, o);
    return !ok && o.min == untouched.min && o.max == untouched.max;
  };
  EXPECT_TRUE(refused({bytes.begin(), bytes.end() - 1}));
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_TRUE(refused(longer));
  EXPECT_TRUE(refused({}));
  for (const float v : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::vector<std::uint8_t> nan = bytes;
    std::memcpy(nan.data() + 4, &v, 4);  // min.y
    EXPECT_TRUE(refused(nan)) << v;
  }
  EXPECT_TRUE(refused(encode_grid_bounds({glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(1.0f)})));  // min.y > max.y
  EXPECT_TRUE(refused(encode_grid_bounds({glm::vec3(-3e38f), glm::vec3(3e38f)})));  // extent overflows
}

}  // namespace
}  // namespace ddish::net
