// Packed RGB SH for the GPU and the wire: IEEE half floats, or a shared-exponent form when a
// probe holds values that fp16 cannot (|v| > 65504, e.g. next to a 1e6-radiance emitter).
//
// Layout of one probe of order L, n = (L+1)^2 coefficients: 3n + 1 16-bit words (host
// endianness), coefficient-major (c0.r, c0.g, c0.b, c1.r, ...), then one meta word:
//   bits 0-2   caller flags (e.g. probe inactive), stored and returned untouched
//   bit  3     0: the 3n words are IEEE halves; 1: shared-exponent form
//   bits 4-15  shared-exponent form only: a 4-bit exponent e_c per channel (R bits 4-7,
//              G 8-11, B 12-15); zero in the fp16 form
// L2 is 27 + 1 words = 56 bytes (PackedL2), in both forms, so a probe can switch form without
// moving. Shared-exponent form: each word is a two's-complement mantissa m in [-32767, 32767],
// value = m * 2^(2 e_c - 16). Scales run from 2^-16 to 2^14 in steps of 4, so a channel keeps
// at least 13 significant bits (error <= max|channel| / 16383, or <= 2^-17 for tiny channels)
// and values up to 32767 * 2^14 = 5.4e8 fit: a 1e6 radiance filling the sphere has an L0
// coefficient of 3.5e6. It is more precise than fp16 for the largest value of a channel but
// keeps no relative precision for values far below it, which is why fp16 is preferred.
// Neither packer ever writes Inf or NaN: out-of-range values saturate, NaN becomes 0, and the
// returned status says so.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "sh/sh_rgb.h"

namespace ddish::sh {

enum class PackStatus {
  kOk,         // every value represented (within the form's rounding)
  kOverflow,   // some |value| too large for the form: saturated to the largest finite value
  kNotFinite,  // some value is NaN (written as 0) or infinite (saturated)
  kBadSize,    // the output span is shorter than packed_words(order); nothing written
};
enum class PackFormat { kHalf, kSharedExp };

inline constexpr std::uint16_t kMetaFlagsMask = 0x0007;
inline constexpr std::uint16_t kMetaSharedExp = 0x0008;
inline constexpr float kHalfMax = 65504.0f;
inline constexpr float kSharedExpMax = 32767.0f * 16384.0f;

constexpr int packed_words(int order) { return 3 * coeff_count(order) + 1; }
constexpr int packed_bytes(int order) { return 2 * packed_words(order); }

// IEEE 754 binary16, round to nearest, ties to even; |f| >= 65520 gives +-Inf, NaN a quiet NaN.
std::uint16_t float_to_half(float f);
float half_to_float(std::uint16_t h);

// Packs sh (its own order) into out[0 .. packed_words(sh.order)).
PackStatus pack_half(const ShRgb& sh, std::uint16_t flags, std::span<std::uint16_t> out);
PackStatus pack_shared_exp(const ShRgb& sh, std::uint16_t flags, std::span<std::uint16_t> out);
// fp16 when every value is finite and |v| <= 65504, else the shared-exponent form; `used`
// (optional) receives the form chosen. kOk unless a value is NaN/Inf or beyond 5.4e8.
PackStatus pack(const ShRgb& sh, std::uint16_t flags, std::span<std::uint16_t> out,
                PackFormat* used = nullptr);

// Decodes either form (read from the meta word); `in` must hold packed_words(order) words.
ShRgb unpack(std::span<const std::uint16_t> in, int order);
std::uint16_t packed_flags(std::span<const std::uint16_t> in, int order);
PackFormat packed_format(std::span<const std::uint16_t> in, int order);

// The default probe: L2 RGB, 56 bytes.
struct PackedL2 {
  std::array<std::uint16_t, packed_words(2)> words{};
};
static_assert(sizeof(PackedL2) == 56, "an L2 probe packs into 56 bytes");

// Packs the L0-L2 bands of sh (higher bands are dropped, missing ones are zero), as pack().
PackStatus pack_l2(const ShRgb& sh, std::uint16_t flags, PackedL2& out,
                   PackFormat* used = nullptr);
ShRgb unpack_l2(const PackedL2& in);

}  // namespace ddish::sh
