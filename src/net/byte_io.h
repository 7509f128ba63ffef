// Little-endian byte writing and bounds-checked reading for the probe stream's wire format.
// The reader never reads past its span: every get reports failure instead, so a decoder built
// on it cannot overrun a truncated or lying message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace ddish::net {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { uint_le(v, 2); }
  void u32(std::uint32_t v) { uint_le(v, 4); }
  void u64(std::uint64_t v) { uint_le(v, 8); }
  void i64(std::int64_t v) { uint_le(static_cast<std::uint64_t>(v), 8); }
  void f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(bits);
  }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, 8);
    u64(bits);
  }
  // LEB128: 7 bits per byte, low bits first, high bit set on all but the last byte.
  void varint(std::uint32_t v) {
    while (v >= 0x80u) {
      out_.push_back(static_cast<std::uint8_t>(v | 0x80u));
      v >>= 7;
    }
    out_.push_back(static_cast<std::uint8_t>(v));
  }
  void bytes(std::span<const std::uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }

 private:
  void uint_le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> in) : in_(in) {}

  std::size_t remaining() const { return in_.size() - pos_; }
  std::size_t position() const { return pos_; }

  bool u8(std::uint8_t& v) { return uint_le(v, 1); }
  bool u16(std::uint16_t& v) { return uint_le(v, 2); }
  bool u32(std::uint32_t& v) { return uint_le(v, 4); }
  bool u64(std::uint64_t& v) { return uint_le(v, 8); }
  bool i64(std::int64_t& v) {
    std::uint64_t u;
    if (!uint_le(u, 8)) return false;
    v = static_cast<std::int64_t>(u);
    return true;
  }
  bool f32(float& v) {
    std::uint32_t bits;
    if (!uint_le(bits, 4)) return false;
    std::memcpy(&v, &bits, 4);
    return true;
  }
  bool f64(double& v) {
    std::uint64_t bits;
    if (!uint_le(bits, 8)) return false;
    std::memcpy(&v, &bits, 8);
    return true;
  }
  // At most 5 bytes; fails on a value above 2^32 - 1 or an over-long encoding.
  bool varint(std::uint32_t& v) {
    std::uint64_t value = 0;
    for (int i = 0; i < 5; ++i) {
      std::uint8_t b;
      if (!u8(b)) return false;
      value |= std::uint64_t(b & 0x7fu) << (7 * i);
      if ((b & 0x80u) == 0) {
        if (value > 0xffffffffull) return false;
        v = static_cast<std::uint32_t>(value);
        return true;
      }
    }
    return false;
  }
  // A view of the next n bytes (fails, consuming nothing, when fewer remain).
  bool bytes(std::size_t n, std::span<const std::uint8_t>& out) {
    if (n > remaining()) return false;
    out = in_.subspan(pos_, n);
    pos_ += n;
    return true;
  }

 private:
  template <typename T>
  bool uint_le(T& v, int n) {
    if (remaining() < std::size_t(n)) return false;
    std::uint64_t value = 0;
    for (int i = 0; i < n; ++i) value |= std::uint64_t(in_[pos_ + std::size_t(i)]) << (8 * i);
    pos_ += std::size_t(n);
    v = static_cast<T>(value);
    return true;
  }
  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
};

}  // namespace ddish::net
