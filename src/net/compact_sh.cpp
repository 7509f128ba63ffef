#include "net/compact_sh.h"

#include <algorithm>
#include <cmath>

namespace ddish::net {
namespace {

class BitWriter {
 public:
  explicit BitWriter(std::span<std::uint8_t> out) : out_(out) {
    std::fill(out_.begin(), out_.end(), std::uint8_t(0));
  }
  void put(std::uint32_t value, int bits) {
    for (int i = 0; i < bits; ++i, ++pos_)
      if ((value >> i) & 1u) out_[pos_ / 8] |= std::uint8_t(1u << (pos_ % 8));
  }

 private:
  std::span<std::uint8_t> out_;
  std::size_t pos_ = 0;
};

class BitReader {
 public:
  explicit BitReader(std::span<const std::uint8_t> in) : in_(in) {}
  std::uint32_t get(int bits) {
    std::uint32_t v = 0;
    for (int i = 0; i < bits; ++i, ++pos_)
      if ((in_[pos_ / 8] >> (pos_ % 8)) & 1u) v |= 1u << i;
    return v;
  }
  std::size_t position() const { return pos_; }

 private:
  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
};

constexpr std::uint32_t kMantissaMax = (1u << kCompactL0Bits) - 1u;
constexpr int kExponentMax = (1 << kCompactExponentBits) - 1;

int qmax(int band) { return (1 << (compact_coefficient_bits(band) - 1)) - 1; }
float band_bound(int band) { return std::sqrt(float(2 * band + 1)); }

float channel(const glm::vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }
float& channel(glm::vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

}  // namespace

bool encode_compact(std::span<const glm::vec3> coefficients, int order,
                    std::span<std::uint8_t> out) {
  bool exact = true;
  BitWriter w(out.first(std::size_t(compact_bytes(order))));
  // L0: clean (a radiance L0 is >= 0 and finite), then the smallest exponent that holds the
  // brightest channel in 12 bits.
  float l0[3];
  float brightest = 0.0f;
  for (int c = 0; c < 3; ++c) {
    float v = channel(coefficients[0], c);
    if (!(v >= 0.0f)) {  // negative or NaN
      exact = false;
      v = 0.0f;
    }
    l0[c] = v;
    brightest = std::max(brightest, v);
  }
  int exponent = 0;
  if (brightest > 0.0f) {
    int e2 = 0;
    std::frexp(brightest, &e2);  // brightest = f 2^e2, f in [0.5, 1)
    exponent = std::clamp(e2 - kCompactL0Bits + kCompactExponentBias, 0, kExponentMax);
    if (exponent < kExponentMax &&
        std::lround(double(brightest) / std::ldexp(1.0, exponent - kCompactExponentBias)) >
            long(kMantissaMax))
      ++exponent;  // rounding carried into a 13th bit
  }
  const double scale = std::ldexp(1.0, exponent - kCompactExponentBias);
  w.put(std::uint32_t(exponent), kCompactExponentBits);
  float l0_decoded[3];
  for (int c = 0; c < 3; ++c) {
    double m = std::round(double(l0[c]) / scale);
    if (m > double(kMantissaMax)) {  // beyond 3.4e10, or infinite
      exact = false;
      m = double(kMantissaMax);
    }
    w.put(std::uint32_t(m), kCompactL0Bits);
    l0_decoded[c] = float(m * scale);
  }
  // Bands: ratios to the decoded L0's bound, so the error does not include L0's rounding.
  int first = 1;
  for (int l = 1; l <= order; ++l) {
    const int count = 2 * l + 1;
    const float bound = band_bound(l);
    float largest = 0.0f;
    for (int i = first; i < first + count; ++i)
      for (int c = 0; c < 3; ++c) {
        const float limit = bound * l0_decoded[c];
        const float v = channel(coefficients[std::size_t(i)], c);
        if (limit > 0.0f && std::isfinite(v)) largest = std::max(largest, std::fabs(v) / limit);
      }
    int range = 0;
    while (range < 3 && largest <= std::ldexp(1.0f, -(range + 1))) ++range;
    w.put(std::uint32_t(range), kCompactRangeBits);
    const int q_max = qmax(l);
    const int bits = compact_coefficient_bits(l);
    for (int i = first; i < first + count; ++i)
      for (int c = 0; c < 3; ++c) {
        const float limit = bound * l0_decoded[c] * std::ldexp(1.0f, -range);
        const float v = channel(coefficients[std::size_t(i)], c);
        double q = 0.0;
        if (limit > 0.0f && !std::isnan(v)) q = std::round(double(v) / limit * q_max);
        if (std::isnan(v) || (limit == 0.0f && v != 0.0f) || std::fabs(q) > q_max) exact = false;
        q = std::clamp(q, double(-q_max), double(q_max));
        w.put(std::uint32_t(std::int32_t(q)) & ((1u << bits) - 1u), bits);
      }
    first += count;
  }
  return exact;
}

bool decode_compact(std::span<const std::uint8_t> in, int order,
                    std::span<glm::vec3> coefficients) {
  const std::size_t bytes = std::size_t(compact_bytes(order));
  BitReader r(in.first(bytes));
  const int exponent = int(r.get(kCompactExponentBits));
  const double scale = std::ldexp(1.0, exponent - kCompactExponentBias);
  for (int c = 0; c < 3; ++c) channel(coefficients[0], c) = float(double(r.get(kCompactL0Bits)) * scale);
  int first = 1;
  for (int l = 1; l <= order; ++l) {
    const int count = 2 * l + 1;
    const int range = int(r.get(kCompactRangeBits));
    const int bits = compact_coefficient_bits(l);
    const int q_max = qmax(l);
    const float step = band_bound(l) * std::ldexp(1.0f, -range) / float(q_max);
    for (int i = first; i < first + count; ++i)
      for (int c = 0; c < 3; ++c) {
        std::int32_t q = std::int32_t(r.get(bits));
        if (q >= (1 << (bits - 1))) q -= 1 << bits;  // two's complement
        if (q < -q_max) return false;
        channel(coefficients[std::size_t(i)], c) = float(q) * step * channel(coefficients[0], c);
      }
    first += count;
  }
  // Padding bits of the last byte must be zero: a canonical code only.
  while (r.position() < bytes * 8)
    if (r.get(1) != 0) return false;
  return true;
}

}  // namespace ddish::net
