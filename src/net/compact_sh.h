// The compact probe encoding of the probe stream: 28 bytes per L2 RGB probe (fp16 is 54, the
// shared-exponent form 56), for radiance probes, whose coefficients are bounded by their own L0.
//
// For a non-negative function f, |c_lm| = |∫ f Y_lm| <= max|Y_lm| ∫ f = sqrt(2l + 1) c_00 per
// channel (max|Y_lm| <= sqrt((2l+1) / 4π) by the addition theorem, c_00 = ∫ f / sqrt(4π)), and a
// probe's running average of projected radiance keeps that bound. So:
//   - L0: one shared exponent E (6 bits) and three 12-bit mantissas m_c (R, G, B):
//     c_00 = m_c 2^(E - 40): 2^-40 .. 4095 × 2^23 = 3.4e10, 12 bits relative to the brightest
//     channel (error <= 2^-12 of it; a negative or NaN L0 is written as 0);
//   - each band l >= 1: a 2-bit range k (shared by the band's coefficients and channels), then
//     per coefficient and channel a signed b_l-bit integer q (b_1 = 8, b_l = 7 above):
//     c_lm = q / qmax_l × 2^-k × sqrt(2l + 1) × c_00 (decoded), qmax_l = 2^(b_l - 1) - 1. k is
//     the largest of 0..3 with every |c_lm| <= 2^-k sqrt(2l+1) c_00 of the band: smooth light
//     (small high bands) gets up to 8 times finer steps.
// Error of a coefficient of band l and channel c: <= 0.5 / qmax_l × 2^-k × sqrt(2l+1) × c_00,c
// (0.68% of c_00 at l = 1, 1.77% at l = 2, for k = 0), plus, only for a coefficient beyond the
// bound (not radiance, or c_00 rounded down past it), what lies beyond it (clamped and counted).
//
// Bits, low bit first, in the order above (L0, then bands 1..L, each band coefficient-major:
// c_l,-l .. c_l,l, R G B within a coefficient); the unused high bits of the last byte are zero.
// L1: 15 bytes, L2: 28, L3: 47, L4: 71.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace ddish::net {

inline constexpr int kCompactExponentBits = 6;
inline constexpr int kCompactExponentBias = 40;
inline constexpr int kCompactL0Bits = 12;
inline constexpr int kCompactRangeBits = 2;

constexpr int compact_coefficient_bits(int band) { return band == 1 ? 8 : 7; }

constexpr int compact_bits(int order) {
  int bits = kCompactExponentBits + 3 * kCompactL0Bits;
  for (int l = 1; l <= order; ++l)
    bits += kCompactRangeBits + 3 * (2 * l + 1) * compact_coefficient_bits(l);
  return bits;
}
constexpr int compact_bytes(int order) { return (compact_bits(order) + 7) / 8; }
static_assert(compact_bytes(2) == 28, "a compact L2 probe is 28 bytes");

// Encodes coefficients[0 .. (order+1)^2) into out[0 .. compact_bytes(order)). Returns false when
// some value had to be clamped (outside the radiance bound, negative L0, NaN or beyond range);
// what is written is then the nearest representable probe. order 1..4; out must be large enough.
bool encode_compact(std::span<const glm::vec3> coefficients, int order, std::span<std::uint8_t> out);

// Decodes compact_bytes(order) bytes into coefficients[0 .. (order+1)^2). Returns false, leaving
// nothing promised in `coefficients`, for a code no encoder writes (q = -2^(b-1), non-zero
// padding bits). Every decoded value is finite.
bool decode_compact(std::span<const std::uint8_t> in, int order, std::span<glm::vec3> coefficients);

}  // namespace ddish::net
