#include "sh/packing.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace ddish::sh {
namespace {

std::size_t to_size(int n) { return static_cast<std::size_t>(n); }

// Rounds m / 2^shift to nearest, ties to even (shift >= 1).
std::uint32_t round_shift(std::uint32_t m, int shift) {
  const std::uint32_t q = m >> shift;
  const std::uint32_t rem = m & ((1u << shift) - 1u);
  const std::uint32_t halfway = 1u << (shift - 1);
  return (rem > halfway || (rem == halfway && (q & 1u))) ? q + 1u : q;
}

// Worse status wins: NaN/Inf over overflow over ok.
PackStatus worse(PackStatus a, PackStatus b) { return int(a) > int(b) ? a : b; }

int channel_exponent_shift(int e) { return 2 * e - 16; }

}  // namespace

std::uint16_t float_to_half(float f) {
  const std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  const auto sign = static_cast<std::uint16_t>((u >> 16) & 0x8000u);
  const std::uint32_t a = u & 0x7fffffffu;
  if (a > 0x7f800000u) return static_cast<std::uint16_t>(sign | 0x7e00u);  // NaN
  if (a >= 0x477ff000u) return static_cast<std::uint16_t>(sign | 0x7c00u);  // >= 65520: Inf
  if (a >= 0x38800000u) {  // >= 2^-14: a normal half; rounding may carry into the exponent
    return static_cast<std::uint16_t>(sign | round_shift(a - 0x38000000u, 13));
  }
  if (a <= 0x33000000u) return sign;  // <= 2^-25: rounds to zero (2^-25 is a tie to even 0)
  // Subnormal half: units of 2^-24. The float is normal here, so its mantissa has the
  // implicit bit; value = m * 2^(e - 150), in half units m * 2^(e - 126).
  const std::uint32_t m = (a & 0x7fffffu) | 0x800000u;
  const int e = int(a >> 23);
  return static_cast<std::uint16_t>(sign | round_shift(m, 126 - e));
}

float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = std::uint32_t(h & 0x8000u) << 16;
  const std::uint32_t e = (h >> 10) & 0x1fu;
  const std::uint32_t m = h & 0x3ffu;
  if (e == 0) {  // zero or subnormal: m * 2^-24 is exact in float
    const float v = float(m) * 0x1p-24f;
    return sign ? -v : v;
  }
  if (e == 31) return std::bit_cast<float>(sign | 0x7f800000u | (m << 13));
  return std::bit_cast<float>(sign | ((e + 112u) << 23) | (m << 13));
}

PackStatus pack_half(const ShRgb& sh, std::uint16_t flags, std::span<std::uint16_t> out) {
  const int n = sh.count();
  if (out.size() < to_size(packed_words(sh.order))) return PackStatus::kBadSize;
  PackStatus status = PackStatus::kOk;
  for (int i = 0; i < n; ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      float v = sh[i][ch];
      if (std::isnan(v)) {
        status = worse(status, PackStatus::kNotFinite);
        v = 0.0f;
      } else if (std::fabs(v) > kHalfMax) {
        status = worse(status, std::isinf(v) ? PackStatus::kNotFinite : PackStatus::kOverflow);
        v = std::copysign(kHalfMax, v);
      }
      out[to_size(3 * i + ch)] = float_to_half(v);
    }
  }
  out[to_size(3 * n)] = static_cast<std::uint16_t>(flags & kMetaFlagsMask);
  return status;
}

PackStatus pack_shared_exp(const ShRgb& sh, std::uint16_t flags, std::span<std::uint16_t> out) {
  const int n = sh.count();
  if (out.size() < to_size(packed_words(sh.order))) return PackStatus::kBadSize;
  PackStatus status = PackStatus::kOk;
  std::uint16_t meta = static_cast<std::uint16_t>((flags & kMetaFlagsMask) | kMetaSharedExp);
  for (int ch = 0; ch < 3; ++ch) {
    float max_c = 0.0f;
    for (int i = 0; i < n; ++i) {
      const float v = sh[i][ch];
      if (std::isnan(v) || std::isinf(v)) {
        status = worse(status, PackStatus::kNotFinite);
        if (std::isnan(v)) continue;
      }
      max_c = std::max(max_c, std::fabs(v));
    }
    // The smallest scale whose rounded mantissas stay within +-32767: the most precision.
    int e = 0;
    while (e < 15 && max_c / std::ldexp(1.0f, channel_exponent_shift(e)) >= 32767.5f) ++e;
    const float inv_scale = std::ldexp(1.0f, -channel_exponent_shift(e));
    for (int i = 0; i < n; ++i) {
      const float v = sh[i][ch];
      long q = 0;
      if (!std::isnan(v)) {
        const float s = v * inv_scale;  // exact: a power-of-two scale
        if (std::fabs(s) >= 32767.5f) {
          if (!std::isinf(v)) status = worse(status, PackStatus::kOverflow);
          q = s > 0.0f ? 32767 : -32767;
        } else {
          q = std::lround(s);
        }
      }
      out[to_size(3 * i + ch)] = static_cast<std::uint16_t>(static_cast<std::int16_t>(q));
    }
    meta = static_cast<std::uint16_t>(meta | (e << (4 + 4 * ch)));
  }
  out[to_size(3 * n)] = meta;
  return status;
}

PackStatus pack(const ShRgb& sh, std::uint16_t flags, std::span<std::uint16_t> out,
                PackFormat* used) {
  const bool fits_half = all_finite(sh) && max_abs(sh) <= kHalfMax;
  if (used) *used = fits_half ? PackFormat::kHalf : PackFormat::kSharedExp;
  return fits_half ? pack_half(sh, flags, out) : pack_shared_exp(sh, flags, out);
}

PackFormat packed_format(std::span<const std::uint16_t> in, int order) {
  return (in[to_size(3 * coeff_count(ShRgb::clamp_order(order)))] & kMetaSharedExp)
             ? PackFormat::kSharedExp
             : PackFormat::kHalf;
}

std::uint16_t packed_flags(std::span<const std::uint16_t> in, int order) {
  return static_cast<std::uint16_t>(in[to_size(3 * coeff_count(ShRgb::clamp_order(order)))] &
                                    kMetaFlagsMask);
}

ShRgb unpack(std::span<const std::uint16_t> in, int order) {
  ShRgb sh(order);
  const int n = sh.count();
  if (in.size() < to_size(packed_words(sh.order))) return sh;
  const std::uint16_t meta = in[to_size(3 * n)];
  const bool shared = (meta & kMetaSharedExp) != 0;
  for (int ch = 0; ch < 3; ++ch) {
    const int e = (meta >> (4 + 4 * ch)) & 0xf;
    const float scale = std::ldexp(1.0f, channel_exponent_shift(e));
    for (int i = 0; i < n; ++i) {
      const std::uint16_t w = in[to_size(3 * i + ch)];
      sh[i][ch] = shared ? float(static_cast<std::int16_t>(w)) * scale : half_to_float(w);
    }
  }
  return sh;
}

PackStatus pack_l2(const ShRgb& sh, std::uint16_t flags, PackedL2& out, PackFormat* used) {
  ShRgb l2 = sh;
  l2.set_order(2);
  return pack(l2, flags, out.words, used);
}

ShRgb unpack_l2(const PackedL2& in) { return unpack(in.words, 2); }

}  // namespace ddish::sh
