// The per-probe coefficient encodings of the probe stream (one per frame, in its header):
//   fp16            3 (L+1)^2 IEEE halves, R G B per coefficient: 54 bytes at L2. Values
//                   beyond ±65504 saturate (counted), NaN is sent as 0.
//   shared-exponent the sh module's shared-exponent form (sh/packing.h), 3 (L+1)^2 mantissas and
//                   the meta word with four-bit exponents per channel: 56 bytes at L2, holds
//                   values up to 5.4e8 (next to very bright emitters).
//   compact         compact_sh.h: L0 shared exponent, higher bands as ratios to it: 28 bytes at L2.
// All little-endian. Decoding checks each probe: a half that is Inf or NaN, a shared-exponent
// meta word with flag bits or without its form bit, a compact code no encoder writes: rejected.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

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

}  // namespace ddish::net
