// The per-probe coefficient encodings of the probe stream (one per frame, in its header):
//   fp16            3 (L+1)^2 IEEE halves, R G B per coefficient: 54 bytes at L2. Values
//                   beyond ±65504 saturate (counted), NaN is sent as 0.
//   shared-exponent the sh module's shared-exponent form (sh/packing.h), 3 (L+1)^2 mantissas and
//                   the meta word with four-bit exponents per channel: 56 bytes at L2, holds
//                   values up to 5.4e8 (next to very bright emitters).
//   compact         compact_sh.h: L0 shared exponent, higher bands as ratios to it: 28 bytes at L2.
// Distance moments (probes/moment_map.h) travel as fp16, per texel the mean distance and the
// mean squared distance, divided by the range (or its square), so in [0, 1]: 4 R^2 bytes, 256
// at R = 8. The rasterizer keeps them as fp16 too (raster/probe_slots.h), so a client's GPU
// holds exactly the halves an in-process render's does. Coarser codes cost image quality
// against the in-process render (docs/protocol.md: 8-bit unorm 47-48 dB, 10-bit 54-61 dB,
// 12-bit 66-68 dB); texels interleaved compress better under zstd than planes (125 against 139
// bytes per probe on the Cornell box).
// All little-endian. Decoding checks each probe: a half that is Inf or NaN, a shared-exponent
// meta word with flag bits or without its form bit, a compact code no encoder writes: rejected.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace ddish::net {

enum class Encoding : std::uint8_t { kHalf = 0, kSharedExp = 1, kCompact = 2 };
inline constexpr int kEncodingCount = 3;

// "fp16", "shared-exponent", "compact"; parse_encoding accepts these names.
std::string encoding_name(Encoding encoding);
std::optional<Encoding> parse_encoding(std::string_view name);

// Bytes of one probe of SH order 1..4.
int probe_bytes(Encoding encoding, int order);

// Encodes (order+1)^2 RGB coefficients into out[0 .. probe_bytes). Returns false when a value
// had to be saturated or replaced (NaN): what is written is the nearest representable probe,
// never Inf or NaN.
bool encode_probe(Encoding encoding, int order, std::span<const glm::vec3> coefficients,
                  std::span<std::uint8_t> out);

// Decodes probe_bytes(encoding, order) bytes; false for a code no encoder writes (then
// `coefficients` holds nothing meaningful). Decoded values are always finite.
bool decode_probe(Encoding encoding, int order, std::span<const std::uint8_t> in,
                  std::span<glm::vec3> coefficients);

// Bytes of one probe's moment map of `texels` texels (R^2).
inline constexpr std::size_t moment_bytes(int texels) { return 4 * std::size_t(texels); }

// Encodes (mean, mean square) per texel into out[0 .. moment_bytes). Returns false when a value
// was outside [0, 1] or NaN: it is written clamped (NaN as 1, nothing within the range).
bool encode_moments(std::span<const glm::vec2> moments, std::span<std::uint8_t> out);

// Decodes moment_bytes(moments.size()) bytes; false (with the texel in *bad) for a half that is
// not a number in [0, 1].
bool decode_moments(std::span<const std::uint8_t> in, std::span<glm::vec2> moments,
                    std::size_t* bad = nullptr);

}  // namespace ddish::net
