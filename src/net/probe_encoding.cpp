#include "net/probe_encoding.h"

#include <algorithm>
#include <cmath>

#include "net/compact_sh.h"
#include "sh/packing.h"

namespace ddish::net {
namespace {

int coefficients_of(int order) { return (order + 1) * (order + 1); }

std::uint16_t load16(std::span<const std::uint8_t> in, std::size_t word) {
  return std::uint16_t(in[2 * word] | (in[2 * word + 1] << 8));
}
void store16(std::span<std::uint8_t> out, std::size_t word, std::uint16_t v) {
  out[2 * word] = std::uint8_t(v);
  out[2 * word + 1] = std::uint8_t(v >> 8);
}

bool encode_half(int order, std::span<const glm::vec3> coefficients, std::span<std::uint8_t> out) {
  bool exact = true;
  std::size_t word = 0;
  for (int i = 0; i < coefficients_of(order); ++i)
    for (int c = 0; c < 3; ++c) {
      float v = coefficients[std::size_t(i)][c];
      if (std::isnan(v)) {
        exact = false;
        v = 0.0f;
      } else if (std::fabs(v) > sh::kHalfMax) {
        exact = false;
        v = std::copysign(sh::kHalfMax, v);
      }
      store16(out, word++, sh::float_to_half(v));
    }
  return exact;
}

bool decode_half(int order, std::span<const std::uint8_t> in, std::span<glm::vec3> coefficients) {
  std::size_t word = 0;
  for (int i = 0; i < coefficients_of(order); ++i)
    for (int c = 0; c < 3; ++c) {
      const std::uint16_t h = load16(in, word++);
      if ((h & 0x7c00u) == 0x7c00u) return false;  // Inf or NaN
      coefficients[std::size_t(i)][c] = sh::half_to_float(h);
    }
  return true;
}

sh::ShRgb to_sh(int order, std::span<const glm::vec3> coefficients) {
  sh::ShRgb s(order);
  for (int i = 0; i < s.count(); ++i) s[i] = coefficients[std::size_t(i)];
  return s;
}

bool encode_shared_exp(int order, std::span<const glm::vec3> coefficients,
                       std::span<std::uint8_t> out) {
  std::uint16_t words[sh::packed_words(4)];
  const int n = sh::packed_words(order);
  const sh::PackStatus status = sh::pack_shared_exp(to_sh(order, coefficients), 0,
                                                    std::span<std::uint16_t>(words, std::size_t(n)));
  for (int w = 0; w < n; ++w) store16(out, std::size_t(w), words[w]);
  return status == sh::PackStatus::kOk;
}

bool decode_shared_exp(int order, std::span<const std::uint8_t> in,
                       std::span<glm::vec3> coefficients) {
  std::uint16_t words[sh::packed_words(4)];
  const int n = sh::packed_words(order);
  for (int w = 0; w < n; ++w) words[w] = load16(in, std::size_t(w));
  const std::uint16_t meta = words[n - 1];
  // The stream's probes carry no flags in the meta word (flags travel in the frame) and always
  // the shared-exponent form bit.
  if ((meta & sh::kMetaFlagsMask) != 0 || (meta & sh::kMetaSharedExp) == 0) return false;
  const sh::ShRgb s = sh::unpack(std::span<const std::uint16_t>(words, std::size_t(n)), order);
  for (int i = 0; i < s.count(); ++i) coefficients[std::size_t(i)] = s[i];
  return true;
}

}  // namespace

std::string encoding_name(Encoding encoding) {
  switch (encoding) {
    case Encoding::kHalf: return "fp16";
    case Encoding::kSharedExp: return "shared-exponent";
    case Encoding::kCompact: return "compact";
  }
  return "unknown";
}

std::optional<Encoding> parse_encoding(std::string_view name) {
  for (int e = 0; e < kEncodingCount; ++e)
    if (name == encoding_name(Encoding(e))) return Encoding(e);
  return std::nullopt;
}

int probe_bytes(Encoding encoding, int order) {
  switch (encoding) {
    case Encoding::kHalf: return 2 * 3 * coefficients_of(order);
    case Encoding::kSharedExp: return sh::packed_bytes(order);
    case Encoding::kCompact: return compact_bytes(order);
  }
  return 0;
}

bool encode_probe(Encoding encoding, int order, std::span<const glm::vec3> coefficients,
                  std::span<std::uint8_t> out) {
  switch (encoding) {
    case Encoding::kHalf: return encode_half(order, coefficients, out);
    case Encoding::kSharedExp: return encode_shared_exp(order, coefficients, out);
    case Encoding::kCompact: return encode_compact(coefficients, order, out);
  }
  return false;
}

bool decode_probe(Encoding encoding, int order, std::span<const std::uint8_t> in,
                  std::span<glm::vec3> coefficients) {
  switch (encoding) {
    case Encoding::kHalf: return decode_half(order, in, coefficients);
    case Encoding::kSharedExp: return decode_shared_exp(order, in, coefficients);
    case Encoding::kCompact: return decode_compact(in, order, coefficients);
  }
  return false;
}

namespace {
std::uint16_t moment_half(float v, bool& exact) {
  if (!(v >= 0.0f && v <= 1.0f)) {
    exact = false;
    v = std::isnan(v) ? 1.0f : std::clamp(v, 0.0f, 1.0f);
  }
  return sh::float_to_half(v);
}
}  // namespace

bool encode_moments(std::span<const glm::vec2> moments, std::span<std::uint8_t> out) {
  bool exact = true;
  for (std::size_t t = 0; t < moments.size(); ++t) {
    store16(out, 2 * t, moment_half(moments[t].x, exact));
    store16(out, 2 * t + 1, moment_half(moments[t].y, exact));
  }
  return exact;
}

bool decode_moments(std::span<const std::uint8_t> in, std::span<glm::vec2> moments, std::size_t* bad) {
  for (std::size_t w = 0; w < 2 * moments.size(); ++w) {
    // 0x0000 .. 0x3c00 are the halves in [0, 1]: no sign bit, nothing above one.
    const std::uint16_t h = load16(in, w);
    if (h > 0x3c00u) {
      if (bad) *bad = w / 2;
      return false;
    }
    moments[w / 2][int(w % 2)] = sh::half_to_float(h);
  }
  return true;
}

}  // namespace ddish::net
